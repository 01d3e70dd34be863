// COIL-100 objects as ObjectModels for the engine and index tests: the CEDD (cedd-lire) of every
// view objN__A.png, extracted once per test binary and cached.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "client/image_file.h"
#include "core/base/mutex.h"
#include "core/descriptor/cedd.h"
#include "core/model/object_model.h"
#include "tests/support/test_data.h"

namespace orbit::testing {

// Object N of COIL-100 (1..100) with its 72 views (azimuths 0, 5, ..., 355); id = N, name objN.
inline const ObjectModel& CoilObject(int number) {
  static Mutex mutex;
  static std::map<int, ObjectModel> cache;  // guarded by mutex (a function's static)
  MutexLock lock(&mutex);
  auto [it, inserted] = cache.try_emplace(number);
  if (inserted) {
    ObjectModel& model = it->second;
    model.id = number;
    model.name = "obj" + std::to_string(number);
    model.variant = DescriptorVariant::kCeddLire;
    for (int azimuth = 0; azimuth < 360; azimuth += 5) {
      const std::string file =
          (DataDir() / "coil-100" /
           ("obj" + std::to_string(number) + "__" + std::to_string(azimuth) + ".png"))
              .string();
      ModelView view;
      view.descriptor = ExtractCedd(ReadImageFile(file), DescriptorVariant::kCeddLire).values;
      view.azimuth = azimuth;
      model.views.push_back(view);
    }
  }
  return it->second;
}

// Objects first..last, keeping only the views whose azimuth satisfies `keep`.
inline std::vector<ObjectModel> CoilObjects(int first, int last,
                                            const std::function<bool(int azimuth)>& keep) {
  std::vector<ObjectModel> models;
  for (int n = first; n <= last; ++n) {
    ObjectModel model = CoilObject(n);
    std::erase_if(model.views,
                  [&](const ModelView& v) { return !keep(static_cast<int>(v.azimuth)); });
    models.push_back(std::move(model));
  }
  return models;
}

// Views at multiples of 10 degrees: the model half of the tests' even/odd split.
inline bool EvenView(int azimuth) { return azimuth % 10 == 0; }

// The view of object `number` at `azimuth` (a multiple of 5).
inline const DescriptorValues& CoilView(int number, int azimuth) {
  return CoilObject(number).views[azimuth / 5].descriptor;
}

// `count` look-alike objects made of COIL-100's, for catalogues larger than COIL-100: object k
// (id k + 1, name look-alikeK) is COIL-100's object k % 100 + 1 with four views, those at
// 5 * (k / 100) degrees plus multiples of 90. Objects 100 apart are the same object seen 5
// degrees further round: alike, but no two share a view (up to 1,800 objects).
inline std::vector<ObjectModel> CoilLookAlikes(int count) {
  std::vector<ObjectModel> models;
  for (int k = 0; k < count; ++k) {
    const int offset = 5 * (k / 100);
    ObjectModel model = CoilObject(k % 100 + 1);
    model.id = k + 1;
    model.name = "look-alike" + std::to_string(k);
    std::erase_if(model.views, [&](const ModelView& v) {
      return (static_cast<int>(v.azimuth) - offset) % 90 != 0;
    });
    models.push_back(std::move(model));
  }
  return models;
}

}  // namespace orbit::testing
