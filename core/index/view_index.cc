#include "core/index/view_index.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>
#include <unordered_set>

#if defined(__SSE2__)
#include <emmintrin.h>  // SSE2: part of every x86-64 CPU, so no runtime dispatch is needed
#endif

#include <flann/flann.hpp>

#include "core/base/cpu_dispatch.h"
#include "core/base/parallel_for.h"
#include "core/descriptor/similarity.h"
#include "core/index/summary_graph.h"

namespace orbit {

using KdTree = flann::Index<flann::L2<float>>;

// The summary graphs' links per node (hnswlib's M) and breadth of search while building
// (ef_construction): docs/results/scale.md, "Choosing the candidate index".
constexpr std::size_t kSummaryGraphLinks = 16;
constexpr std::size_t kSummaryGraphBuildBreadth = 100;
// Summaries asked of a graph per object wanted (see ViewIndexSnapshot::CandidatesKdTree).
constexpr std::size_t kSummaryRowsPerObject = 4;

// Views of some objects in one contiguous block, never modified after BuildSegment.
struct ViewIndexSnapshot::Segment {
  std::vector<std::shared_ptr<const IndexedObject>> objects;
  std::vector<std::size_t> first_view;  // per object: its first view's local slot
  std::size_t view_count = 0;
  // Values per view: the variant's DescriptorLength (the rest of every descriptor is 0), so a
  // CEDD segment scans 144 values, not 480.
  int length = kDescriptorSize;
  // kExact mode: every view's descriptor side by side, local slot s at [s * length, (s + 1) *
  // length), the stream the exact scan reads. kKdTree mode: empty, and each view is read in its
  // object's model, which the segment keeps alive: a catalogue searched through its summary
  // graphs does not hold every descriptor twice (docs/design.md#view-index).
  std::vector<std::uint8_t> descriptors;
  std::vector<std::int32_t> squared_norms;   // c.c per local slot
  std::vector<std::int32_t> object_of_view;  // local object index per local slot

  // Where local object o's views are: its first view's descriptor, and the bytes from one view's
  // to the next.
  struct Views {
    const std::uint8_t* first;
    std::size_t stride;
  };
  Views ObjectViews(std::size_t o) const {
    if (!descriptors.empty()) {
      return {&descriptors[first_view[o] * length], static_cast<std::size_t>(length)};
    }
    return {objects[o]->model().views.front().descriptor.data(), sizeof(ModelView)};
  }
  // Local slot s's descriptor (its first `length` values).
  const std::uint8_t* View(std::size_t s) const {
    if (!descriptors.empty()) return &descriptors[s * length];
    const std::size_t o = object_of_view[s];
    return objects[o]->model().views[s - first_view[o]].descriptor.data();
  }
  // kKdTree mode only, built by the first view search that needs it (ViewTree): the product's
  // engine never searches views, so a server pays for the trees (their float copy of every
  // descriptor, and the build's time before serving) only when a session of a thesis' engine
  // asks (docs/design.md#view-index).
  mutable std::once_flag kd_tree_built;
  mutable std::vector<float> points;        // the descriptors as floats, for FLANN
  mutable std::unique_ptr<KdTree> kd_tree;  // reads `points`

  // The segment's kd-trees, built on the first call; every later or concurrent call returns the
  // same trees once built.
  const KdTree& ViewTree(int trees) const {
    std::call_once(kd_tree_built, [&] {
      points.resize(view_count * length);
      for (std::size_t s = 0; s < view_count; ++s) {
        std::copy_n(View(s), length, points.begin() + static_cast<std::ptrdiff_t>(s * length));
      }
      flann::Matrix<float> matrix(points.data(), view_count, length);
      kd_tree = std::make_unique<KdTree>(matrix, flann::KDTreeIndexParams(trees));
      // Not reproducible: Debian's FLANN 1.9.2 shuffles the points of each tree with a
      // std::random_device, so two builds over the same views give different trees (and
      // kd-tree searches can return slightly different lists;
      // docs/results/coil100-reproduction.md measures the spread). Builds in different
      // threads are independent.
      kd_tree->buildIndex();
    });
    return *kd_tree;
  }
  // kKdTree mode only: a graph of the objects' summaries in cosine order, summary s of local
  // object o (its sector mean's first `length` values) labelled o * kSummarySectors + s. The
  // graph keeps them only rounded (SummaryGraph::Metric::kCosineBytes); the exact values are
  // the objects' own sectors.
  std::unique_ptr<SummaryGraph> summary_graph;
};

// A segment as one snapshot sees it: which of its objects are still present.
struct ViewIndexSnapshot::SegmentState {
  std::shared_ptr<const Segment> segment;
  std::vector<bool> alive;  // per object of the segment
  std::size_t dead_views = 0;
};

namespace {

using Segment = ViewIndexSnapshot::Segment;
using SegmentState = ViewIndexSnapshot::SegmentState;

// The query widened to 16 bits once, so that each view costs nine 16-byte multiply-adds.
struct WideQuery {
  alignas(16) std::int16_t values[kDescriptorSize];
  std::int32_t squared_norm = 0;

  explicit WideQuery(const DescriptorValues& query) {
    for (int i = 0; i < kDescriptorSize; ++i) {
      values[i] = query[i];
      squared_norm += query[i] * query[i];
    }
  }
};

// q.c for one view of `length` values (a multiple of 16), exact (values are at most 7, so 16-bit
// products and 32-bit sums never overflow): the portable path, which the compiler vectorises
// where the target has vectors (NEON on arm64).
ORBIT_HOT_LOOP std::int32_t PortableDot(const WideQuery& query, const std::uint8_t* view,
                                        int length) {
  std::int32_t sum = 0;
  for (int i = 0; i < length; ++i) sum += query.values[i] * view[i];
  return sum;
}

#if defined(__SSE2__)
// PortableDot in SSE2 intrinsics: nine 16-byte multiply-adds per CEDD view. The same integer sum,
// so the same result.
std::int32_t Sse2Dot(const WideQuery& query, const std::uint8_t* view, int length) {
  const __m128i zero = _mm_setzero_si128();
  __m128i sum = _mm_setzero_si128();
  for (int i = 0; i < length; i += 16) {
    const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(view + i));
    const __m128i low = _mm_unpacklo_epi8(bytes, zero);
    const __m128i high = _mm_unpackhi_epi8(bytes, zero);
    const __m128i q_low = _mm_load_si128(reinterpret_cast<const __m128i*>(query.values + i));
    const __m128i q_high = _mm_load_si128(reinterpret_cast<const __m128i*>(query.values + i + 8));
    sum = _mm_add_epi32(sum, _mm_madd_epi16(low, q_low));
    sum = _mm_add_epi32(sum, _mm_madd_epi16(high, q_high));
  }
  sum = _mm_add_epi32(sum, _mm_shuffle_epi32(sum, _MM_SHUFFLE(1, 0, 3, 2)));
  sum = _mm_add_epi32(sum, _mm_shuffle_epi32(sum, _MM_SHUFFLE(2, 3, 0, 1)));
  return _mm_cvtsi128_si32(sum);
}
#endif

// q.c on the active hot-loop path (core/base/cpu_dispatch.h).
std::int32_t Dot(const WideQuery& query, const std::uint8_t* view, int length) {
#if defined(__SSE2__)
  if (ActiveHotLoopPath() == HotLoopPath::kFastest) return Sse2Dot(query, view, length);
#endif
  return PortableDot(query, view, length);
}

// TC from the integer products, with Tanimoto()'s conventions for zero vectors.
double TanimotoFromDot(std::int32_t qc, std::int32_t qq, std::int32_t cc) {
  if (qq == 0 && cc == 0) return 1.0;
  return static_cast<double>(qc) / (qq + cc - qc);
}

// (similarity, slot) ordered best first: higher similarity, then lower slot.
using Scored = std::pair<double, std::size_t>;
bool Better(const Scored& a, const Scored& b) {
  return a.first > b.first || (a.first == b.first && a.second < b.second);
}

// A segment of `objects`, built on `threads` threads when it holds more than
// kOneThreadBuildsUpTo objects.
std::shared_ptr<const Segment> BuildSegment(
    std::vector<std::shared_ptr<const IndexedObject>> objects, const ViewIndexOptions& options,
    int threads = 1) {
  auto segment = std::make_shared<Segment>();
  static_assert(kCeddSize % 16 == 0 && kDescriptorSize % 16 == 0);
  if (!objects.empty()) segment->length = DescriptorLength(objects.front()->model().variant);
  const int length = segment->length;
  for (const auto& object : objects) {
    segment->first_view.push_back(segment->view_count);
    segment->view_count += object->view_count();
  }
  const bool copy = options.search == SearchMode::kExact;
  if (copy) segment->descriptors.reserve(segment->view_count * length);
  for (std::size_t o = 0; o < objects.size(); ++o) {
    for (const ModelView& view : objects[o]->model().views) {
      if (copy) {
        segment->descriptors.insert(segment->descriptors.end(), view.descriptor.begin(),
                                    view.descriptor.begin() + length);
      }
      std::int32_t norm = 0;
      for (const std::uint8_t value : view.descriptor) norm += value * value;
      segment->squared_norms.push_back(norm);
      segment->object_of_view.push_back(static_cast<std::int32_t>(o));
    }
  }
  segment->objects = std::move(objects);
  if (options.search == SearchMode::kKdTree && !segment->objects.empty()) {
    const auto& built = segment->objects;
    if (built.size() <= kOneThreadBuildsUpTo) threads = 1;
    segment->summary_graph = std::make_unique<SummaryGraph>(
        length, built.size() * kSummarySectors,
        SummaryGraph::Options{.metric = SummaryGraph::Metric::kCosineBytes,
                              .links = kSummaryGraphLinks,
                              .build_breadth = kSummaryGraphBuildBreadth});
    SummaryGraph& graph = *segment->summary_graph;
    const auto add = [&](std::size_t row) {
      const SectorViews& sectors = built[row / kSummarySectors]->Sectors(kSummarySectors);
      graph.Add(sectors.descriptor[row % kSummarySectors].data(), row);
    };
    // On one thread, rows are inserted in order with hnswlib's fixed seed: the same segment
    // gives the same graph on every build. On several, the first row is the entry point that
    // the others link to; then they race (hnswlib locks each node it links).
    add(0);
    ParallelFor(built.size() * kSummarySectors - 1, threads, [&](std::size_t i) { add(i + 1); });
  }
  return segment;
}

SegmentState FreshState(std::shared_ptr<const Segment> segment) {
  SegmentState state;
  state.alive.assign(segment->objects.size(), true);
  state.segment = std::move(segment);
  return state;
}

// The live objects of some segments, oldest first, in one new segment.
SegmentState Merge(const std::vector<const SegmentState*>& parts, const ViewIndexOptions& options) {
  std::vector<std::shared_ptr<const IndexedObject>> objects;
  for (const SegmentState* part : parts) {
    for (std::size_t o = 0; o < part->segment->objects.size(); ++o) {
      if (part->alive[o]) objects.push_back(part->segment->objects[o]);
    }
  }
  return FreshState(BuildSegment(std::move(objects), options));
}

std::size_t LiveViews(const SegmentState& state) {
  return state.segment->view_count - state.dead_views;
}

void ValidateOptions(const ViewIndexOptions& options) {
  if (options.kd_trees < 1) throw std::invalid_argument("kd_trees must be at least 1");
  if (options.kd_checks < 1) throw std::invalid_argument("kd_checks must be at least 1");
  if (options.kd_candidates < 1) throw std::invalid_argument("kd_candidates must be at least 1");
  if (options.build_threads < 1) throw std::invalid_argument("build_threads must be at least 1");
}

std::shared_ptr<const IndexedObject> Prepare(ObjectModel model, DescriptorVariant variant) {
  if (model.variant != variant) {
    throw std::invalid_argument("object " + std::to_string(model.id) + " has variant " +
                                std::string(VariantName(model.variant)) + ", the index holds " +
                                std::string(VariantName(variant)));
  }
  return std::make_shared<const IndexedObject>(std::move(model));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// ViewIndexSnapshot

ViewIndexSnapshot::ViewIndexSnapshot(DescriptorVariant variant, ViewIndexOptions options,
                                     std::vector<SegmentState> segments)
    : variant_(variant), options_(options), segments_(std::move(segments)) {
  static std::atomic<std::uint64_t> next_serial{1};
  serial_ = next_serial.fetch_add(1, std::memory_order_relaxed);
  for (const SegmentState& state : segments_) {
    const Segment& segment = *state.segment;
    segment_first_slot_.push_back(slot_count_);
    position_of_slot_.resize(slot_count_ + segment.view_count, -1);
    view_of_slot_.resize(slot_count_ + segment.view_count, 0);
    std::vector<std::int32_t>& position_of_object = position_of_object_.emplace_back();
    position_of_object.assign(segment.objects.size(), -1);
    std::size_t& live_objects = segment_live_objects_.emplace_back(0);
    for (std::size_t o = 0; o < segment.objects.size(); ++o) {
      const std::size_t first = slot_count_ + segment.first_view[o];
      const int views = segment.objects[o]->view_count();
      for (int v = 0; v < views; ++v) view_of_slot_[first + v] = v;
      if (!state.alive[o]) continue;
      const auto position = static_cast<std::int32_t>(objects_.size());
      position_of_object[o] = position;
      ++live_objects;
      std::fill_n(position_of_slot_.begin() + static_cast<std::ptrdiff_t>(first), views, position);
      position_of_id_[segment.objects[o]->id()] = objects_.size();
      objects_.push_back({segment.objects[o].get(), first});
      view_count_ += views;
    }
    slot_count_ += segment.view_count;
  }
}

ViewIndexSnapshot::~ViewIndexSnapshot() = default;

const IndexedObject* ViewIndexSnapshot::Find(ObjectId id) const {
  const auto it = position_of_id_.find(id);
  return it == position_of_id_.end() ? nullptr : objects_[it->second].object;
}

std::vector<ViewMatch> ViewIndexSnapshot::Search(const DescriptorValues& query, int count) const {
  if (count < 1) throw std::invalid_argument("search count must be at least 1");
  return options_.search == SearchMode::kKdTree ? SearchKdTree(query, count)
                                                : SearchExact(query, count);
}

std::vector<ViewMatch> ViewIndexSnapshot::SearchExact(const DescriptorValues& query,
                                                      int count) const {
  if (count < 1) throw std::invalid_argument("search count must be at least 1");
  const WideQuery wide(query);
  // The best `count` so far as a heap whose top is the worst of them. Slots arrive in
  // increasing order, so an equal similarity never displaces the worst kept.
  std::vector<Scored> best;
  const auto worse_on_top = [](const Scored& a, const Scored& b) { return Better(a, b); };
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    const Segment& segment = *segments_[s].segment;
    for (std::size_t o = 0; o < segment.objects.size(); ++o) {
      if (!segments_[s].alive[o]) continue;
      const std::size_t first = segment.first_view[o];
      const std::size_t end = first + segment.objects[o]->view_count();
      const Segment::Views views = segment.ObjectViews(o);
      for (std::size_t v = first; v < end; ++v) {
        const double tc =
            TanimotoFromDot(Dot(wide, views.first + (v - first) * views.stride, segment.length),
                            wide.squared_norm, segment.squared_norms[v]);
        if (static_cast<int>(best.size()) < count) {
          best.emplace_back(tc, segment_first_slot_[s] + v);
          std::push_heap(best.begin(), best.end(), worse_on_top);
        } else if (tc > best.front().first) {
          std::pop_heap(best.begin(), best.end(), worse_on_top);
          best.back() = {tc, segment_first_slot_[s] + v};
          std::push_heap(best.begin(), best.end(), worse_on_top);
        }
      }
    }
  }
  return Best(best, count);
}

std::vector<ViewMatch> ViewIndexSnapshot::SearchKdTree(const DescriptorValues& query,
                                                       int count) const {
  const WideQuery wide(query);
  std::vector<float> point(query.begin(), query.end());
  std::vector<Scored> scored;
  std::vector<std::size_t> indices;
  std::vector<float> distances;
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    const SegmentState& state = segments_[s];
    const Segment& segment = *state.segment;
    if (LiveViews(state) == 0) continue;
    // Ask for enough that deleted views cannot crowd out the live candidates.
    const std::size_t wanted = std::min(
        segment.view_count,
        static_cast<std::size_t>(std::max(count, options_.kd_candidates)) + state.dead_views);
    indices.assign(wanted, 0);
    distances.assign(wanted, 0);
    flann::Matrix<std::size_t> index_matrix(indices.data(), 1, wanted);
    flann::Matrix<float> distance_matrix(distances.data(), 1, wanted);
    const flann::Matrix<float> queries(point.data(), 1, segment.length);  // the segment's dims
    const int found = segment.ViewTree(options_.kd_trees)
                          .knnSearch(queries, index_matrix, distance_matrix, wanted,
                                     flann::SearchParams(options_.kd_checks));
    for (int i = 0; i < found; ++i) {
      const std::size_t local = indices[i];
      if (local >= segment.view_count || !state.alive[segment.object_of_view[local]]) continue;
      const double tc = TanimotoFromDot(Dot(wide, segment.View(local), segment.length),
                                        wide.squared_norm, segment.squared_norms[local]);
      scored.emplace_back(tc, segment_first_slot_[s] + local);
    }
  }
  return Best(scored, count);
}

namespace {

// query . summary over `length` values in eight interleaved partial sums, added pairwise at the
// end: a fixed order (so every path gives the same value, docs/design.md#exactness) that the
// compiler vectorises, where one running sum is a chain of dependent additions. A scan of every
// object's summaries (the exact mode's candidates) is this loop over every summary.
ORBIT_HOT_LOOP float SummaryDot(const float* __restrict query, const float* __restrict summary,
                                int length) {
  float lanes[8] = {};
  int i = 0;
  for (; i + 8 <= length; i += 8) {
    for (int k = 0; k < 8; ++k) lanes[k] += query[i + k] * summary[i + k];
  }
  for (int k = 0; i < length; ++i, ++k) lanes[k] += query[i] * summary[i];
  return ((lanes[0] + lanes[4]) + (lanes[1] + lanes[5])) +
         ((lanes[2] + lanes[6]) + (lanes[3] + lanes[7]));
}

// TC(query, summary) in float over `length` values, with Tanimoto()'s conventions for zero
// vectors; `summary_norm` is summary . summary.
float SummaryTanimoto(const std::vector<float>& query, float query_norm, const float* summary,
                      float summary_norm, int length) {
  const float qc = RunHotLoop<SummaryDot>(query.data(), summary, length);
  if (query_norm == 0 && summary_norm == 0) return 1.0f;
  const float denominator = query_norm + summary_norm - qc;
  return denominator > 0 ? qc / denominator : 0.0f;
}

// The best `count` of per-object similarities, best first, ties to the lower position.
std::vector<ObjectCandidate> BestObjects(std::vector<ObjectCandidate> scored, int count) {
  const auto better = [](const ObjectCandidate& a, const ObjectCandidate& b) {
    return a.similarity > b.similarity || (a.similarity == b.similarity && a.position < b.position);
  };
  const std::size_t kept = std::min(scored.size(), static_cast<std::size_t>(count));
  std::partial_sort(scored.begin(), scored.begin() + static_cast<std::ptrdiff_t>(kept),
                    scored.end(), better);
  scored.resize(kept);
  return scored;
}

}  // namespace

std::vector<ObjectCandidate> ViewIndexSnapshot::ObjectCandidates(const DescriptorValues& query,
                                                                 int count) const {
  if (count < 1) throw std::invalid_argument("candidate count must be at least 1");
  if (options_.search == SearchMode::kKdTree && objects_.size() > static_cast<std::size_t>(count)) {
    return CandidatesKdTree(query, count);
  }
  return CandidatesExact(query, count);
}

std::vector<ObjectCandidate> ViewIndexSnapshot::CandidatesExact(const DescriptorValues& query,
                                                                int count) const {
  const std::vector<float> point(query.begin(), query.end());
  float query_norm = 0;
  for (const float v : point) query_norm += v * v;
  std::vector<ObjectCandidate> scored;
  scored.reserve(objects_.size());
  std::size_t position = 0;
  for (const SegmentState& state : segments_) {
    const Segment& segment = *state.segment;
    for (std::size_t o = 0; o < segment.objects.size(); ++o) {
      if (!state.alive[o]) continue;
      const SectorViews& sectors = segment.objects[o]->Sectors(kSummarySectors);
      float best = 0;
      for (int s = 0; s < kSummarySectors; ++s) {
        best = std::max(
            best, SummaryTanimoto(point, query_norm, sectors.descriptor[s].data(),
                                  static_cast<float>(sectors.squared_norm[s]), segment.length));
      }
      scored.push_back({position++, best});
    }
  }
  return BestObjects(std::move(scored), count);
}

std::vector<ObjectCandidate> ViewIndexSnapshot::CandidatesKdTree(const DescriptorValues& query,
                                                                 int count) const {
  std::vector<float> point(query.begin(), query.end());
  float query_norm = 0;
  for (const float v : point) query_norm += v * v;
  // Each object's best summary among those found, by position.
  std::unordered_map<std::size_t, float> best;
  std::vector<std::size_t> found;  // summary rows, from a segment's graph
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    const Segment& segment = *segments_[s].segment;
    const std::size_t rows = segment.objects.size() * kSummarySectors;
    const std::vector<std::int32_t>& position_of = position_of_object_[s];
    const std::size_t live = segment_live_objects_[s];
    const std::size_t dead = segment.objects.size() - live;
    if (live == 0) continue;
    // An object's summaries are alike, so a list of summaries holds fewer objects: ask for
    // kSummaryRowsPerObject per object wanted, plus the deleted objects' summaries, doubling
    // while the list holds fewer live objects than wanted (or than the segment has).
    const std::size_t objects_wanted = std::min(live, static_cast<std::size_t>(count));
    std::size_t wanted =
        std::min(rows, kSummaryRowsPerObject * objects_wanted + dead * kSummarySectors);
    std::unordered_map<std::size_t, float> found_here;
    for (;;) {
      found_here.clear();
      segment.summary_graph->Search(point.data(), wanted, found);
      for (const std::size_t row : found) {
        const std::size_t local = row / kSummarySectors;
        const std::int32_t position = position_of[local];
        if (position < 0) continue;
        const SectorViews& sectors = segment.objects[local]->Sectors(kSummarySectors);
        const std::size_t sector = row % kSummarySectors;
        const float tc =
            SummaryTanimoto(point, query_norm, sectors.descriptor[sector].data(),
                            static_cast<float>(sectors.squared_norm[sector]), segment.length);
        float& kept = found_here.try_emplace(static_cast<std::size_t>(position), tc).first->second;
        kept = std::max(kept, tc);
      }
      if (found_here.size() >= objects_wanted || wanted == rows) break;
      wanted = std::min(rows, 2 * wanted);
    }
    best.insert(found_here.begin(), found_here.end());
  }
  std::vector<ObjectCandidate> scored;
  scored.reserve(best.size());
  for (const auto& [position, similarity] : best) scored.push_back({position, similarity});
  return BestObjects(std::move(scored), count);
}

std::vector<ViewMatch> ViewIndexSnapshot::Best(const std::vector<Scored>& scored, int count) const {
  std::vector<Scored> sorted = scored;
  std::sort(sorted.begin(), sorted.end(), Better);
  if (static_cast<int>(sorted.size()) > count) sorted.resize(count);
  std::vector<ViewMatch> matches;
  matches.reserve(sorted.size());
  for (const auto& [similarity, slot] : sorted) {
    const IndexedObject& object = *objects_[position_of_slot_[slot]].object;
    const int view = view_of_slot_[slot];
    matches.push_back({object.id(), view, object.model().views[view].azimuth, similarity});
  }
  return matches;
}

std::shared_ptr<const ViewIndexSnapshot> ViewIndexSnapshot::With(
    std::vector<ObjectModel> models) const {
  std::vector<SegmentState> segments = segments_;
  if (!models.empty()) {
    std::vector<std::shared_ptr<const IndexedObject>> objects;
    std::unordered_set<ObjectId> ids;
    for (ObjectModel& model : models) {
      if (position_of_id_.contains(model.id) || !ids.insert(model.id).second) {
        throw std::invalid_argument("two models share the id " + std::to_string(model.id));
      }
      objects.push_back(Prepare(std::move(model), variant_));
    }
    segments.push_back(FreshState(BuildSegment(std::move(objects), options_)));
  }
  return std::make_shared<const ViewIndexSnapshot>(variant_, options_, std::move(segments));
}

std::shared_ptr<const void> ViewIndexSnapshot::Derived(
    DerivedKey key, const std::function<std::shared_ptr<const void>()>& build) const {
  MutexLock lock(&derived_mutex_);
  std::shared_ptr<const void>& derived = derived_[key];
  if (!derived) derived = build();
  return derived;
}

std::shared_ptr<const SnapshotChange> ViewIndexSnapshot::ChangeSince(
    const ViewIndexSnapshot& before) const {
  return std::static_pointer_cast<const SnapshotChange>(
      Derived({"change-since", static_cast<std::int64_t>(before.serial())},
              [&]() -> std::shared_ptr<const void> {
                return std::make_shared<const SnapshotChange>(CompareSnapshots(before, *this));
              }));
}

SnapshotChange CompareSnapshots(const ViewIndexSnapshot& before, const ViewIndexSnapshot& after) {
  // An object is kept when the other snapshot has the same version (IndexedObject) under its id.
  const auto position_in = [](const ViewIndexSnapshot& snapshot,
                              const IndexedObject* object) -> std::int32_t {
    if (snapshot.Find(object->id()) != object) return -1;
    return static_cast<std::int32_t>(snapshot.PositionOf(object->id()));
  };
  SnapshotChange change;
  for (const ObjectSlot& slot : before.objects()) {
    if (position_in(after, slot.object) < 0) change.removed.push_back(slot.object);
  }
  std::size_t next = 0;  // position in `after`
  for (const ObjectSlot& slot : after.objects()) {
    const std::int32_t position = position_in(before, slot.object);
    const bool added = position < 0;
    const std::size_t source = added ? change.added.size() : static_cast<std::size_t>(position);
    std::vector<SnapshotChange::Run>& runs = change.runs;
    if (!runs.empty() && runs.back().added == added &&
        runs.back().source + runs.back().length == source) {
      ++runs.back().length;
    } else {
      runs.push_back({next, source, 1, added});
    }
    ++next;
    if (added) change.added.push_back(slot);
  }
  return change;
}

void ViewIndexSnapshot::SimilarityToEveryView(const DescriptorValues& query,
                                              std::vector<float>& similarities) const {
  const WideQuery wide(query);
  similarities.resize(slot_count_);
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    const Segment& segment = *segments_[s].segment;
    float* out = similarities.data() + segment_first_slot_[s];
    for (std::size_t o = 0; o < segment.objects.size(); ++o) {
      const Segment::Views views = segment.ObjectViews(o);
      const std::size_t first = segment.first_view[o];
      const std::size_t end = first + segment.objects[o]->view_count();
      for (std::size_t v = first; v < end; ++v) {
        out[v] = static_cast<float>(
            TanimotoFromDot(Dot(wide, views.first + (v - first) * views.stride, segment.length),
                            wide.squared_norm, segment.squared_norms[v]));
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// ViewIndex

ViewIndex::ViewIndex(DescriptorVariant variant, ViewIndexOptions options)
    : variant_(variant), options_(options) {
  ValidateOptions(options_);
  current_ =
      std::make_shared<const ViewIndexSnapshot>(variant_, options_, std::vector<SegmentState>{});
}

namespace {
DescriptorVariant VariantOf(const std::vector<ObjectModel>& models) {
  if (models.empty()) {
    throw std::invalid_argument("ViewIndex needs at least one model to know its variant");
  }
  return models.front().variant;
}
}  // namespace

ViewIndex::ViewIndex(std::vector<ObjectModel> models, ViewIndexOptions options)
    : variant_(VariantOf(models)), options_(options) {
  ValidateOptions(options_);
  current_ = BuildAll(std::move(models));
}

std::shared_ptr<const ViewIndexSnapshot> ViewIndex::BuildAll(
    std::vector<ObjectModel> models) const {
  std::vector<SegmentState> segments;
  if (!models.empty()) {
    std::unordered_set<ObjectId> ids;
    for (const ObjectModel& model : models) {
      if (!ids.insert(model.id).second) {
        throw std::invalid_argument("two models share the id " + std::to_string(model.id));
      }
    }
    // Each object's preparation is its own: on every build thread (the first invalid model in
    // the list is not necessarily the one reported then).
    std::vector<std::shared_ptr<const IndexedObject>> objects(models.size());
    const int threads = models.size() > kOneThreadBuildsUpTo ? options_.build_threads : 1;
    ParallelFor(models.size(), threads, [&](std::size_t i) {
      objects[i] = Prepare(std::move(models[i]), variant_);
      if (options_.search == SearchMode::kKdTree) objects[i]->Sectors(kSummarySectors);
    });
    segments.push_back(FreshState(BuildSegment(std::move(objects), options_, threads)));
  }
  return std::make_shared<const ViewIndexSnapshot>(variant_, options_, std::move(segments));
}

void ViewIndex::ReplaceAll(std::vector<ObjectModel> models) {
  MutexLock write_lock(&write_mutex_);
  Publish(BuildAll(std::move(models)));
}

namespace {

// Appends a segment holding `object` and merges segments of similar size. Binary-counter
// merging: while the newest segment is at least as large as the one before it, the two become
// one. Segment sizes then fall geometrically, so there are O(log views) segments and each view is
// re-indexed O(log views) times in all.
void AppendObject(std::vector<SegmentState>& segments, std::shared_ptr<const IndexedObject> object,
                  const ViewIndexOptions& options) {
  std::vector<std::shared_ptr<const IndexedObject>> added{std::move(object)};
  segments.push_back(FreshState(BuildSegment(std::move(added), options)));
  while (segments.size() >= 2 &&
         LiveViews(segments.back()) >= LiveViews(segments[segments.size() - 2])) {
    SegmentState merged = Merge({&segments[segments.size() - 2], &segments.back()}, options);
    segments.pop_back();
    segments.back() = std::move(merged);
  }
}

// Marks object `id` deleted in `segments`; false (nothing changed) when it is not there.
bool MarkDeleted(std::vector<SegmentState>& segments, ObjectId id,
                 const ViewIndexOptions& options) {
  for (std::size_t s = 0; s < segments.size(); ++s) {
    SegmentState& state = segments[s];
    const auto& objects = state.segment->objects;
    for (std::size_t o = 0; o < objects.size(); ++o) {
      if (!state.alive[o] || objects[o]->id() != id) continue;
      state.alive[o] = false;
      state.dead_views += objects[o]->view_count();
      // A segment mostly deleted costs searches more than rewriting it does.
      if (LiveViews(state) == 0) {
        segments.erase(segments.begin() + static_cast<std::ptrdiff_t>(s));
      } else if (2 * state.dead_views > state.segment->view_count) {
        state = Merge({&state}, options);
      }
      return true;
    }
  }
  return false;
}

}  // namespace

void ViewIndex::Add(ObjectModel model) {
  MutexLock write_lock(&write_mutex_);
  const std::shared_ptr<const ViewIndexSnapshot> base = Snapshot();
  if (base->Find(model.id) != nullptr) {
    throw std::invalid_argument("an object with id " + std::to_string(model.id) +
                                " is already in the index");
  }
  std::vector<SegmentState> segments = base->segments_;
  AppendObject(segments, Prepare(std::move(model), variant_), options_);
  Publish(std::make_shared<const ViewIndexSnapshot>(variant_, options_, std::move(segments)));
}

void ViewIndex::Replace(ObjectModel model) {
  MutexLock write_lock(&write_mutex_);
  // Validated before anything changes: a refused model leaves the index as it was.
  std::shared_ptr<const IndexedObject> object = Prepare(std::move(model), variant_);
  std::vector<SegmentState> segments = Snapshot()->segments_;
  MarkDeleted(segments, object->id(), options_);
  AppendObject(segments, std::move(object), options_);
  Publish(std::make_shared<const ViewIndexSnapshot>(variant_, options_, std::move(segments)));
}

bool ViewIndex::Remove(ObjectId id) {
  MutexLock write_lock(&write_mutex_);
  std::vector<SegmentState> segments = Snapshot()->segments_;
  if (!MarkDeleted(segments, id, options_)) return false;
  Publish(std::make_shared<const ViewIndexSnapshot>(variant_, options_, std::move(segments)));
  return true;
}

std::shared_ptr<const ViewIndexSnapshot> ViewIndex::Snapshot() const {
  MutexLock lock(&publish_mutex_);
  return current_;
}

void ViewIndex::PrepareSnapshotsWith(SnapshotPreparation prepare) {
  MutexLock write_lock(&write_mutex_);
  prepare_ = std::move(prepare);
}

void ViewIndex::Publish(std::shared_ptr<const ViewIndexSnapshot> next) {
  if (prepare_) {
    try {
      prepare_(*next, *Snapshot());
    } catch (const std::exception&) {
      // A head start only (PrepareSnapshotsWith): the change itself must not be lost.
    }
  }
  MutexLock lock(&publish_mutex_);
  current_ = std::move(next);
}

}  // namespace orbit
