// orbit_capture_client: what a device application does with the Orbit client library - enroll an
// object from a walk around it, or recognise it from another walk - in one small program built
// against the installed package (find_package(OrbitClient), examples/capture_client/).
//
//   orbit_capture_client SERVER VIDEO LOG X,Y,W,H enroll NAME
//   orbit_capture_client SERVER VIDEO LOG X,Y,W,H recognize
//
// SERVER is HOST:PORT (plaintext; see docs/client.md for TLS and tokens), VIDEO any video
// OpenCV reads, LOG its orientation log (docs/capture.md), X,Y,W,H the object's box on the
// first frame. Exit status: 0 done, 1 refused or failed (the reason on stderr), 2 bad usage.
#include <exception>
#include <iostream>
#include <string>

#include "client/capture_reader.h"
#include "client/capture_session.h"
#include "client/connection.h"
#include "client/enroller.h"
#include "client/recognition_session.h"

namespace {

int Enroll(const orbit::Connection& connection, orbit::CaptureReader& capture,
           const std::string& name) {
  orbit::Enroller enroller(connection);
  const orbit::Enroller::VideoEnrollment enrolled = enroller.FromVideo(name, capture);
  std::cout << "enrolled " << enrolled.object.name() << " (id " << enrolled.object.id() << ") from "
            << enrolled.selection.views.size() << " of " << enrolled.selection.frames_read
            << " frames\n";
  return 0;
}

int Recognize(const orbit::Connection& connection, orbit::CaptureReader& capture) {
  orbit::RecognitionOptions options;
  options.top_k = 1;
  options.on_update = [](const orbit::v1::SessionUpdate& update) {
    std::cout << "frame " << update.frame_index();
    if (update.candidates_size() > 0) {
      std::cout << ": " << update.candidates(0).name() << " " << update.candidates(0).score();
    }
    std::cout << "\n";
  };
  auto session = orbit::RecognitionSession::Open(connection, options);
  const orbit::CaptureStreamResult streamed = orbit::StreamCapture(*session, capture);
  const grpc::Status status = session->Close();
  if (!status.ok()) {
    std::cerr << "session ended: " << status.error_message() << "\n";
    return 1;
  }
  std::cout << streamed.frames_sent << " frames sent, " << streamed.frames_lost << " lost\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 5 ? argv[5] : "";
  if (!((mode == "enroll" && argc == 7) || (mode == "recognize" && argc == 6))) {
    std::cerr << "usage: " << argv[0] << " SERVER VIDEO LOG X,Y,W,H enroll NAME\n"
              << "       " << argv[0] << " SERVER VIDEO LOG X,Y,W,H recognize\n";
    return 2;
  }
  try {
    orbit::ConnectionOptions where;
    where.address = argv[1];
    const orbit::Connection connection(where);
    orbit::CaptureReader capture(argv[2], orbit::OrientationLog::ReadFile(argv[3]),
                                 {.first_box = orbit::ParseBox(argv[4])});
    return mode == "enroll" ? Enroll(connection, capture, argv[6]) : Recognize(connection, capture);
  } catch (const std::exception& e) {
    std::cerr << "orbit_capture_client: " << e.what() << "\n";
    return 1;
  }
}
