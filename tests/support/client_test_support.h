// COIL-100 images as the client library's tests enroll and stream them: objects enrolled from
// every 10th degree (views 0, 10, ..., 350), queried between them (5, 15, ...), so no query
// image is in the model.
#pragma once

#include <thread>

#include <chrono>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "client/connection.h"
#include "client/enroller.h"
#include "client/image_file.h"
#include "client/models_client.h"
#include "client/recognition_session.h"
#include "client/rpc_error.h"
#include "tests/support/test_data.h"

namespace orbit::testing {

inline std::string CoilFile(int object, int azimuth) {
  return (DataDir() / "coil-100" /
          ("obj" + std::to_string(object) + "__" + std::to_string(azimuth) + ".png"))
      .string();
}

// `--image F --azimuth A` arguments of `orbit enroll` / `orbit recognize` for object `object`
// at the given azimuths, each reported `offset` degrees off.
inline std::string CoilImageArguments(int object, const std::vector<int>& azimuths,
                                      int offset = 0) {
  std::string args;
  for (int a : azimuths) {
    args += " --image " + CoilFile(object, a) + " --azimuth " + std::to_string(a + offset);
  }
  return args;
}

// 0, 20, ..., 340.
inline std::vector<int> EveryTwentyDegrees() {
  std::vector<int> azimuths;
  for (int a = 0; a < 360; a += 20) azimuths.push_back(a);
  return azimuths;
}

inline cv::Mat CoilImage(int object, int azimuth) {
  return ReadImageFile(CoilFile(object, azimuth));
}

// A plaintext connection to `address` with no token.
inline ConnectionOptions At(const std::string& address,
                            std::chrono::milliseconds deadline = std::chrono::seconds(10)) {
  ConnectionOptions options;
  options.address = address;
  options.unary_deadline = deadline;
  return options;
}

// Session options with the server's defaults but `top_k` candidates.
inline RecognitionOptions TopK(int top_k) {
  RecognitionOptions options;
  options.top_k = top_k;
  return options;
}

// Object `object`'s views at 0, 10, ..., 350 degrees.
inline std::vector<EnrollmentImage> CoilEnrollmentImages(int object) {
  std::vector<EnrollmentImage> images;
  for (int azimuth = 0; azimuth < 360; azimuth += 10) {
    images.push_back({CoilImage(object, azimuth), static_cast<double>(azimuth), {}, {}});
  }
  return images;
}

// The status code of the RpcError `call` throws; OK when it throws nothing.
template <typename Call>
grpc::StatusCode RpcCodeOf(Call call) {
  try {
    call();
  } catch (const RpcError& e) {
    return e.code();
  }
  return grpc::StatusCode::OK;
}

// Enrolls objects first..last as "objN" through the client library.
// Then waits until the server's accept / unknown rule is calibrated on every object it holds
// (ServerInfo.rule_estimate; asking is what starts a recalibration, which runs at idle priority
// and can wait long on a busy machine): a session then meets the rule of the whole model set.
inline void EnrollCoilObjects(const Connection& connection, int first, int last) {
  Enroller enroller(connection, {.seed = 1, .threads = 2});
  for (int object = first; object <= last; ++object) {
    enroller.Enroll("obj" + std::to_string(object), CoilEnrollmentImages(object));
  }
  ModelsClient models(connection);
  for (int attempt = 0; attempt < 600; ++attempt) {
    const v1::ServerInfoResponse info = models.ServerInfo();
    if (info.object_count() < 2 || info.rule_estimate().objects() == info.object_count()) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ADD_FAILURE() << "the server's calibration did not catch up with its objects in 60 s";
}

}  // namespace orbit::testing
