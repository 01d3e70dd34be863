#include "core/decision/enrollment_feedback.h"

#include <algorithm>
#include <stdexcept>

#include "core/base/angles.h"
#include "core/descriptor/similarity.h"

namespace orbit {
namespace {

// View indices of `object` in azimuth order (ties: stored order).
std::vector<std::size_t> ByAzimuth(const ObjectModel& object) {
  std::vector<std::size_t> order(object.views.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return NormaliseAzimuth(object.views[a].azimuth) < NormaliseAzimuth(object.views[b].azimuth);
  });
  return order;
}

}  // namespace

EnrollmentFeedback AssessEnrollment(const ObjectModel& object, const ViewIndexSnapshot& index) {
  if (object.views.empty())
    throw std::invalid_argument("AssessEnrollment: the object has no views");
  EnrollmentFeedback feedback;
  const std::vector<std::size_t> order = ByAzimuth(object);
  std::vector<double> azimuths;
  for (const ModelView& view : object.views) azimuths.push_back(view.azimuth);
  feedback.gaps = AzimuthGaps(std::move(azimuths), kCoverageGapDegrees);

  // Each view's best TC with the object's other views (for closer_views), and the repeats.
  std::vector<double> own_best(object.views.size(), 0);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const DescriptorValues& view = object.views[order[k]].descriptor;
    bool repeat = false;
    for (std::size_t j = 0; j < order.size(); ++j) {
      if (j == k) continue;
      const double similarity = Tanimoto(view, object.views[order[j]].descriptor);
      own_best[order[k]] = std::max(own_best[order[k]], similarity);
      repeat = repeat || (j < k && similarity >= kRedundantSimilarity);
    }
    if (repeat)
      feedback.redundant_azimuths.push_back(NormaliseAzimuth(object.views[order[k]].azimuth));
  }

  // Other objects' best TC with each view: every object's from one scan of every view per view,
  // or, in a large index, the candidates' only (the header's contract).
  const std::vector<ObjectSlot>& objects = index.objects();
  std::vector<double> similarity_sum(objects.size(), 0);
  std::vector<int> closer(objects.size(), 0);
  std::vector<bool> scored(objects.size(), false);
  const auto add = [&](std::size_t p, std::size_t v, float best) {  // object p's best with view v
    similarity_sum[p] += best;
    closer[p] += object.views.size() > 1 && best > own_best[v];
  };
  if (objects.size() <= kScanEveryObjectUpTo) {
    std::fill(scored.begin(), scored.end(), true);
    std::vector<float> similarities;
    for (std::size_t v = 0; v < object.views.size(); ++v) {
      index.SimilarityToEveryView(object.views[v].descriptor, similarities);
      for (std::size_t p = 0; p < objects.size(); ++p) {
        float best = 0;
        for (int w = 0; w < objects[p].object->view_count(); ++w) {
          best = std::max(best, similarities[objects[p].first_slot + w]);
        }
        add(p, v, best);
      }
    }
  } else {
    // Probes spread round the object: every step-th view in azimuth order.
    const std::size_t step =
        std::max<std::size_t>(1, order.size() / static_cast<std::size_t>(kConfusableProbes));
    for (std::size_t k = 0; k < order.size(); k += step) {
      for (const ObjectCandidate& candidate : index.ObjectCandidates(
               object.views[order[k]].descriptor, kConfusableCandidatesPerProbe)) {
        scored[candidate.position] = true;
      }
    }
    for (std::size_t p = 0; p < objects.size(); ++p) {
      if (!scored[p]) continue;
      const ObjectModel& other = objects[p].object->model();
      for (std::size_t v = 0; v < object.views.size(); ++v) {
        float best = 0;
        for (const ModelView& w : other.views) {
          best = std::max(best,
                          static_cast<float>(Tanimoto(object.views[v].descriptor, w.descriptor)));
        }
        add(p, v, best);
      }
    }
  }
  for (std::size_t p = 0; p < objects.size(); ++p) {
    if (!scored[p] || objects[p].object->id() == object.id) continue;
    feedback.confusable.push_back({objects[p].object->id(),
                                   similarity_sum[p] / static_cast<double>(object.views.size()),
                                   closer[p]});
  }
  const std::size_t kept = std::min<std::size_t>(feedback.confusable.size(), kConfusableObjects);
  std::partial_sort(
      feedback.confusable.begin(), feedback.confusable.begin() + static_cast<std::ptrdiff_t>(kept),
      feedback.confusable.end(), [](const Confusion& a, const Confusion& b) {
        return a.similarity != b.similarity ? a.similarity > b.similarity : a.object < b.object;
      });
  feedback.confusable.resize(kept);
  return feedback;
}

}  // namespace orbit
