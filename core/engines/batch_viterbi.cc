#include "core/engines/batch_viterbi.h"

#include <algorithm>
#include <cfloat>
#include <stdexcept>

#include "core/base/cpu_dispatch.h"

namespace orbit {
namespace {

constexpr std::size_t kMaxStates = 65536;  // back pointers are 16 bits

// The vector kernels below are plain loops over objects, hot loops (core/base/cpu_dispatch.h)
// that the compiler vectorises: the AVX2 path handles 8 objects per instruction.

// next[o] = pi * emission[o]; top[o] = max(top[o], next[o]).
ORBIT_HOT_LOOP void Start(float pi, const float* __restrict emission, float* __restrict next,
                          float* __restrict top, std::size_t n) {
  for (std::size_t o = 0; o < n; ++o) {
    next[o] = pi * emission[o];
    top[o] = std::max(top[o], next[o]);
  }
}

// best[o], arg[o] = score_i[o] * a, i: the first transition into a state.
ORBIT_HOT_LOOP void Enter(const float* __restrict score_i, float a, std::int32_t i,
                          float* __restrict best, std::int32_t* __restrict arg, std::size_t n) {
  for (std::size_t o = 0; o < n; ++o) {
    best[o] = score_i[o] * a;
    arg[o] = i;
  }
}

// best[o], arg[o] = the larger of (best[o], arg[o]) and (score_i[o] * a, i); strict, so that
// among equal values the earlier (lower) state stays.
ORBIT_HOT_LOOP void Relax(const float* __restrict score_i, float a, std::int32_t i,
                          float* __restrict best, std::int32_t* __restrict arg, std::size_t n) {
  for (std::size_t o = 0; o < n; ++o) {
    const float value = score_i[o] * a;
    const bool better = value > best[o];
    best[o] = better ? value : best[o];
    arg[o] = better ? i : arg[o];
  }
}

// next[o] = best[o] * emission[o]; back[o] = arg[o]; top[o] = max(top[o], next[o]).
ORBIT_HOT_LOOP void Emit(const float* __restrict best, const std::int32_t* __restrict arg,
                         const float* __restrict emission, float* __restrict next,
                         std::uint16_t* __restrict back, float* __restrict top, std::size_t n) {
  for (std::size_t o = 0; o < n; ++o) {
    next[o] = best[o] * emission[o];
    back[o] = static_cast<std::uint16_t>(arg[o]);
    top[o] = std::max(top[o], next[o]);
  }
}

// row[o] *= scale[o], and values below FLT_MIN become 0 (see the header).
ORBIT_HOT_LOOP void Rescale(float* __restrict row, const float* __restrict scale, std::size_t n) {
  for (std::size_t o = 0; o < n; ++o) {
    const float value = row[o] * scale[o];
    row[o] = value >= FLT_MIN ? value : 0.0f;
  }
}

// scale[o] = 1 / top[o], or 1 when every score of the object is 0.
ORBIT_HOT_LOOP void Reciprocal(float* __restrict top, std::size_t n) {
  for (std::size_t o = 0; o < n; ++o) top[o] = top[o] > 0.0f ? 1.0f / top[o] : 1.0f;
}

}  // namespace

BatchViterbi::BatchViterbi(std::vector<double> initial) {
  if (initial.empty() || initial.size() > kMaxStates) {
    throw std::invalid_argument("BatchViterbi needs 1..65536 states");
  }
  for (const double pi : initial) initial_.push_back(static_cast<float>(pi));
}

void BatchViterbi::Decode(std::span<const float* const> emissions,
                          std::span<const SparseTransitions* const> steps, std::size_t objects) {
  const std::size_t states = initial_.size();
  frames_ = emissions.size();
  if (frames_ == 0) throw std::invalid_argument("Viterbi needs at least one frame");
  if (steps.size() != frames_ - 1) {
    throw std::invalid_argument("Viterbi needs one transition step between consecutive frames");
  }
  for (const SparseTransitions* step : steps) {
    if (step->states() != states) {
      throw std::invalid_argument("Viterbi: transition size differs from states");
    }
  }
  if (objects == 0) {  // an empty index: no path to find (the loops below index empty rows)
    paths_.clear();
    return;
  }
  // The scratch is the thread's, not the decoder's: a server thread serving many sessions in
  // turn finds it in its cache, where each session's own would be cold.
  thread_local std::vector<float> score, next, best, top;
  thread_local std::vector<std::int32_t> arg;
  thread_local std::vector<std::uint16_t> back_pointers;
  score.resize(states * objects);
  next.resize(states * objects);
  best.resize(objects);
  arg.resize(objects);
  back_pointers.resize(frames_ * states * objects);
  top.resize(objects);

  for (std::size_t t = 0; t < frames_; ++t) {
    const float* emission = emissions[t];
    std::fill(top.begin(), top.end(), 0.0f);
    if (t == 0) {
      for (std::size_t i = 0; i < states; ++i) {
        RunHotLoop<Start>(initial_[i], &emission[i * objects], &next[i * objects], top.data(),
                          objects);
      }
    } else {
      std::uint16_t* back = &back_pointers[t * states * objects];
      for (std::size_t j = 0; j < states; ++j) {
        const std::span<const std::pair<int, float>> into = steps[t - 1]->into(j);
        if (into.empty()) {
          std::fill(best.begin(), best.end(), 0.0f);
          std::fill(arg.begin(), arg.end(), 0);
        }
        for (std::size_t k = 0; k < into.size(); ++k) {
          const auto [i, a] = into[k];
          if (k == 0) {
            RunHotLoop<Enter>(&score[i * objects], a, i, best.data(), arg.data(), objects);
          } else {
            RunHotLoop<Relax>(&score[i * objects], a, i, best.data(), arg.data(), objects);
          }
        }
        RunHotLoop<Emit>(best.data(), arg.data(), &emission[j * objects], &next[j * objects],
                         &back[j * objects], top.data(), objects);
      }
    }
    RunHotLoop<Reciprocal>(top.data(), objects);
    for (std::size_t i = 0; i < states; ++i)
      RunHotLoop<Rescale>(&next[i * objects], top.data(), objects);
    score.swap(next);
  }

  // Backtrack each object from its best final state (lowest index among equals).
  paths_.resize(objects * frames_);
  for (std::size_t o = 0; o < objects; ++o) {
    std::size_t last = 0;
    for (std::size_t i = 1; i < states; ++i) {
      if (score[i * objects + o] > score[last * objects + o]) last = i;
    }
    std::uint16_t* path = &paths_[o * frames_];
    path[frames_ - 1] = static_cast<std::uint16_t>(last);
    for (std::size_t t = frames_ - 1; t > 0; --t) {
      path[t - 1] = back_pointers[(t * states + path[t]) * objects + o];
    }
  }
}

}  // namespace orbit
