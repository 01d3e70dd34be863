// eth-80-dev's ring as `orbit eval --layout manifest --manifest ring.csv --boxes boxes.csv`
// selects it: each image cut to its object's box grown by 10% a side.
#pragma once

#include <string>

#include "evaluation/dataset.h"
#include "tests/support/test_data.h"

namespace orbit::testing {

// `objects` and `unknown_objects` as --objects and --unknown-objects take them ("" for every
// object / none).
inline SelectedImages CroppedEthRing(const std::string& objects,
                                     const std::string& unknown_objects) {
  const auto folder = DataDir() / "eth-80-dev";
  DatasetSelection selection;
  selection.layout = "manifest";
  selection.manifest = folder / "ring.csv";
  selection.objects = objects;
  selection.unknown_objects = unknown_objects;
  SelectedImages images = SelectDataset(selection);
  const auto boxes = ReadBoxes(folder / "boxes.csv");
  AttachBoxes(images.known, boxes, 0.1);
  AttachBoxes(images.unknown, boxes, 0.1);
  return images;
}

}  // namespace orbit::testing
