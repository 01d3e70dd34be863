// orbit loadtest: a load generator for the Recognition.Session API, in the manner of ghz: N
// sessions each stream a dataset's views as a turntable would show them, open loop (a fixed rate
// per session, scheduled by the clock) or closed loop (the next frame as soon as the update
// arrives), optionally beside enrollments; then it reports round trips, throughput, errors by
// status, the server's own figures and the generator's CPU (cli/load_report.h).
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "api/conversion.h"
#include "api/engines/engine_names.h"
#include "api/status_code_name.h"
#include "cli/commands.h"
#include "cli/load_report.h"
#include "cli/load_session.h"
#include "cli/network_options.h"
#include "cli/process_usage.h"
#include "cli/progress_bar.h"
#include "cli/session_flags.h"
#include "client/enroller.h"
#include "client/image_file.h"
#include "client/models_client.h"
#include "client/recognition_session.h"
#include "client/rpc_error.h"
#include "core/base/mutex.h"
#include "core/base/parallel_for.h"
#include "core/descriptor/cedd.h"
#include "evaluation/dataset.h"
#include "server/connection_limits.h"

namespace orbit::cli {
namespace {

using Clock = std::chrono::steady_clock;

// Between opening the streams and the first frame.
constexpr std::chrono::milliseconds kOpeningTime{200};
// How long after the end of the load the updates of frames already sent are awaited; sessions
// still owing updates then are cancelled.
constexpr std::chrono::seconds kDrainTime{10};
// A server limit on frames per second per session (orbit serve --max-fps, 60 by default) at or
// below which a closed loop is bound to be refused.
constexpr double kModestFrameLimit = 1000;

struct LoadtestOptions {
  NetworkOptions network;
  SessionFlags session;
  int sessions = 1;
  int connections = 1;  // TCP connections the sessions share, round robin
  double rate = 0;      // frames/s per session; 0 with --closed-loop
  bool closed_loop = false;
  double duration = 10;  // seconds
  std::string layout = "coil100";
  std::string data = "../shared/data/coil-100";
  std::string manifest;
  std::string objects;  // "": every object of the dataset
  bool image_frames = false;
  double enroll_every = 0;     // seconds between enrollment starts; 0: back to back
  int enroll_count = 0;        // 0: as many as fit in the duration (with --enroll-every)
  bool delete_during = false;  // delete each enrolled object once the next one is enrolled
  int server_pid = 0;
  bool json = false;
};

// The images of the selected objects, and which of them each object has (in the dataset's
// order: by azimuth for COIL-100).
struct Dataset {
  std::vector<DatasetImage> images;
  std::vector<DatasetObject> objects;
};

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The turntable of each object: each view described once, before the load (in `variant`, on
// every core), so no frame costs the generator a descriptor.
std::vector<std::vector<TurntableView>> DescribeTurntables(const Dataset& dataset,
                                                           DescriptorVariant variant,
                                                           bool keep_encoded) {
  std::vector<TurntableView> views(dataset.images.size());
  ParallelFor(views.size(), AvailableCpus(), [&](std::size_t i) {
    const DatasetImage& image = dataset.images[i];
    SetWireDescriptor(ExtractCedd(ReadImageFile(image.path), variant).values, variant,
                      &views[i].cedd, &views[i].appearance);
    if (keep_encoded) views[i].encoded = ReadBytes(image.path);
    views[i].azimuth = image.azimuth;
  });
  std::vector<std::vector<TurntableView>> turntables;
  for (const DatasetObject& object : dataset.objects) {
    std::vector<TurntableView>& turntable = turntables.emplace_back();
    for (std::size_t i : object.images) turntable.push_back(views[i]);
  }
  return turntables;
}

// Enrollments beside the load: `count` objects (0: no limit) with the views of `images`, one
// starting every `every` seconds (0: back to back) from clock.start until clock.end. Counts
// enrollments in flight in `enrolling`; keeps the names enrolled for Delete. With
// `delete_during`, each object is deleted as soon as the next one is enrolled, so the model set
// gains and loses an object every `every` seconds while the sessions run (a soak's churn).
class LoadEnrollments {
 public:
  // Describes the views now (as every enrollment path does, client/enroller.h), and asks the
  // server's variant, so that an enrollment during the load is the Enroll call alone.
  LoadEnrollments(const Connection& connection, const std::vector<EnrollmentImage>& images,
                  double every, int count, bool delete_during)
      : enroller_(connection, {.threads = static_cast<unsigned>(AvailableCpus())}),
        models_(connection),
        views_(enroller_.ComputeViews(images)),
        every_(every),
        count_(count),
        delete_during_(delete_during) {}

  void Run(const LoadClock& clock, std::atomic<int>& enrolling) {
    const std::string prefix = "loadtest-" + std::to_string(::getpid()) + "-";
    for (int k = 0; count_ == 0 || k < count_; ++k) {
      const Clock::time_point due = clock.start + std::chrono::duration_cast<Clock::duration>(
                                                      std::chrono::duration<double>(every_ * k));
      if (due >= clock.end) break;
      std::this_thread::sleep_until(due);
      if (Clock::now() >= clock.end) break;
      const std::string name = prefix + std::to_string(k);
      ++enrolling;
      const Clock::time_point started = Clock::now();
      try {
        enroller_.EnrollViews(name, views_, R"({"source":"orbit loadtest"})");
        latency_.Record(
            std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - started).count());
        enrolled_.push_back(name);
      } catch (const RpcError& e) {
        ++errors_[std::string(StatusCodeName(e.code()))];
      }
      if (delete_during_ && enrolled_.size() > 1) DeleteEnrolled(enrolled_.size() - 2);
      --enrolling;
    }
  }

  // Deletes every object Run enrolled and has not deleted yet.
  void Delete() {
    for (std::size_t i = 0; i < enrolled_.size(); ++i) DeleteEnrolled(i);
  }

  void AddTo(LoadReport& report) const {
    report.enrollments_run = true;
    report.deleted_during = delete_during_;
    report.enrollments_done = static_cast<int>(enrolled_.size());
    report.enrollments_deleted = deleted_;
    report.enrollment_views = static_cast<int>(views_.size());
    report.enrollment.Merge(latency_);
    for (const auto& [name, n] : errors_) report.errors[name] += n;
  }

 private:
  // Deletes enrolled_[i] unless it is already gone.
  void DeleteEnrolled(std::size_t i) {
    if (i < deleted_flags_.size() && deleted_flags_[i]) return;
    deleted_flags_.resize(enrolled_.size(), false);
    deleted_flags_[i] = true;
    try {
      models_.DeleteObject(ObjectByName(enrolled_[i]));
      ++deleted_;
    } catch (const RpcError& e) {
      ++errors_[std::string(StatusCodeName(e.code()))];
    }
  }

  Enroller enroller_;
  ModelsClient models_;
  const std::vector<v1::View> views_;
  const double every_;
  const int count_;
  const bool delete_during_;
  LatencyHistogram latency_;
  std::vector<std::string> enrolled_;
  std::vector<bool> deleted_flags_;  // per enrolled_, once DeleteEnrolled has run for it
  int deleted_ = 0;
  std::map<std::string, std::uint64_t> errors_;
};

// "load [=====>     ]  40% 4/10, 6s left, 2560 frames/s" (seconds of load, updates received
// in the last half second), redrawn on stderr twice a second while the load runs.
class ProgressLine {
 public:
  ProgressLine(const LoadClock& clock, const std::atomic<std::uint64_t>& answered, double duration)
      : thread_([this, &clock, &answered, duration] { Draw(clock, answered, duration); }) {}
  ~ProgressLine() {
    {
      MutexLock lock(&mutex_);
      stop_ = true;
    }
    stopped_.SignalAll();
    thread_.join();
  }

 private:
  void Draw(const LoadClock& clock, const std::atomic<std::uint64_t>& answered, double duration)
      ABSL_LOCKS_EXCLUDED(mutex_) {
    MutexLock lock(&mutex_);
    bool drawn = false;
    std::uint64_t previous = 0;
    Clock::time_point previous_time = clock.start;
    for (;;) {
      const Clock::time_point next_draw = Clock::now() + std::chrono::milliseconds(500);
      while (!stop_ && stopped_.WaitUntil(&mutex_, next_draw)) {
      }
      if (stop_) break;
      const Clock::time_point now = Clock::now();
      if (now < clock.start) continue;
      const double elapsed = std::chrono::duration<double>(now - clock.start).count();
      const std::uint64_t count = answered.load();
      const double rate =
          (count - previous) / std::chrono::duration<double>(now - previous_time).count();
      previous = count;
      previous_time = now;
      const auto done = static_cast<std::size_t>(std::min(elapsed, duration));
      std::cerr << "\r"
                << ProgressBar::Render("load", done, static_cast<std::size_t>(duration),
                                       duration - elapsed)
                << ", " << static_cast<long>(rate) << " frames/s\x1b[K" << std::flush;
      drawn = true;
    }
    if (drawn) std::cerr << "\r\x1b[K" << std::flush;
  }

  Mutex mutex_;
  CondVar stopped_;
  bool stop_ ABSL_GUARDED_BY(mutex_) = false;
  std::thread thread_;
};

Dataset SelectLoadDataset(const LoadtestOptions& options) {
  Dataset dataset;
  dataset.images =
      SelectDataset({options.layout, options.data, options.manifest, options.objects, ""}).known;
  dataset.objects = GroupByObject(dataset.images);
  if (dataset.objects.empty()) throw std::runtime_error("the dataset has no images");
  return dataset;
}

// The images of the object enrolled again and again: the dataset's first object, every view.
std::vector<EnrollmentImage> EnrollmentImages(const Dataset& dataset) {
  std::vector<EnrollmentImage> images;
  for (std::size_t i : dataset.objects.front().images) {
    images.push_back({ReadImageFile(dataset.images[i].path), dataset.images[i].azimuth, {}, {}});
  }
  return images;
}

// The server's usage while sessions are open: a server gone meanwhile leaves its figures out of
// the report rather than abandoning the sessions.
std::optional<ProcessUsage> SampleServer(int pid) {
  try {
    return ReadProcessUsage(pid);
  } catch (const std::runtime_error& e) {
    std::cerr << "orbit loadtest: warning: " << e.what() << "\n";
    return std::nullopt;
  }
}

// The server's resident memory at every tenth of the load, from clock.start to clock.end, into
// `samples` (seconds from the start, bytes); a server gone meanwhile ends the sampling.
void SampleServerMemory(int pid, const LoadClock& clock,
                        std::vector<std::pair<double, std::int64_t>>& samples) {
  constexpr int kIntervals = 10;
  const Clock::duration step = (clock.end - clock.start) / kIntervals;
  for (int i = 0; i <= kIntervals; ++i) {
    const Clock::time_point due = clock.start + step * i;
    std::this_thread::sleep_until(due);
    const std::optional<ProcessUsage> usage = SampleServer(pid);
    if (!usage) return;
    samples.emplace_back(std::chrono::duration<double>(due - clock.start).count(),
                         usage->rss_bytes);
  }
}

// Open loop: session s sends frame k at clock.start + (k + s / N) / rate, so the N sessions'
// frames are spread evenly over each period, as independent devices' would be; one thread
// sends them all (a send only queues the frame). A frame sent late counts its lateness in its
// round trip, which starts at the time it was due.
void SendOnSchedule(const std::vector<std::unique_ptr<LoadSession>>& sessions, double rate,
                    const LoadClock& clock) {
  const std::size_t n = sessions.size();
  const double frames_per_second = rate * static_cast<double>(n);
  for (std::uint64_t j = 0;; ++j) {
    // j / (rate x N) rather than j x step: whole seconds stay exact, so 3 sessions at 20
    // frames/s for 2 s send 120 frames, not 121.
    const Clock::time_point due =
        clock.start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                          static_cast<double>(j) / frames_per_second));
    if (due >= clock.end) return;
    std::this_thread::sleep_until(due);
    sessions[j % n]->SendFrame(static_cast<std::int64_t>(j / n), due);
  }
}

int RunLoadtest(const LoadtestOptions& options) {
  const Connection connection(ToConnectionOptions(options.network));
  const v1::ServerInfoResponse info = ModelsClient(connection).ServerInfo();
  const DescriptorVariant variant = FromProtoVariant(info.variant());
  const double max_fps = info.limits().max_frames_per_second();
  if (!options.closed_loop && options.rate > max_fps) {
    std::cerr << "orbit loadtest: warning: --rate " << options.rate
              << " is above the server's limit of " << max_fps
              << " frames/s per session (orbit serve --max-fps): sessions will be ended\n";
  }
  if (options.closed_loop && max_fps <= kModestFrameLimit) {
    std::cerr << "orbit loadtest: warning: closed loop, and the server ends a session that sends "
                 "more than "
              << max_fps << " frames/s: start it with a higher --max-fps to measure throughput\n";
  }
  // A wrong pid fails the command now, before any session opens.
  if (options.server_pid > 0) ReadProcessUsage(options.server_pid);

  const Dataset dataset = SelectLoadDataset(options);
  const std::vector<std::vector<TurntableView>> turntables =
      DescribeTurntables(dataset, variant, options.image_frames);
  std::optional<LoadEnrollments> enrollments;
  if (options.enroll_count > 0 || options.enroll_every > 0) {
    enrollments.emplace(connection, EnrollmentImages(dataset), options.enroll_every,
                        options.enroll_count, options.delete_during);
  }

  RecognitionOptions session_options = ToRecognitionOptions(options.session);
  const v1::SessionOptions open = ToProtoSessionOptions(session_options, variant);
  LoadReport report;
  report.server = options.network.server;
  report.engine = SessionEngineName(session_options.engine != v1::ENGINE_UNSPECIFIED
                                        ? session_options.engine
                                        : info.session_defaults().engine());
  report.sessions = options.sessions;
  if (!options.closed_loop) report.rate = options.rate;
  report.duration_seconds = options.duration;
  report.image_frames = options.image_frames;

  LoadClock clock;
  std::atomic<int> enrolling{0};
  std::atomic<std::uint64_t> answered{0};
  const LoadShared shared{clock, enrolling, answered};
  report.connections = options.connections;
  // Session s streams on connections[s mod N]. With one, every session shares `connection`;
  // with more, each is a TCP connection of its own, as separate devices' would be.
  std::vector<std::unique_ptr<Connection>> own_connections;
  std::vector<const Connection*> connections{&connection};
  if (options.connections > 1) {
    ConnectionOptions separate = connection.options();
    separate.own_connection = true;
    connections.clear();
    for (int c = 0; c < options.connections; ++c) {
      own_connections.push_back(std::make_unique<Connection>(separate));
      connections.push_back(own_connections.back().get());
    }
  }
  std::vector<std::unique_ptr<v1::Recognition::Stub>> stubs;
  for (const Connection* c : connections) stubs.push_back(v1::Recognition::NewStub(c->channel()));
  std::vector<std::unique_ptr<LoadSession>> sessions;
  for (int s = 0; s < options.sessions; ++s) {
    sessions.push_back(std::make_unique<LoadSession>(
        s, turntables[static_cast<std::size_t>(s) % turntables.size()], options.image_frames,
        options.closed_loop, shared));
  }
  // Every stream is opened before the clock starts, so the load measures frames only.
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    const std::size_t c = s % connections.size();
    sessions[s]->Start(*stubs[c], *connections[c], open);
  }

  if (options.server_pid > 0) report.server_start = SampleServer(options.server_pid);
  const double cpu_at_start = OwnCpuSeconds();
  clock.start = Clock::now() + kOpeningTime;
  clock.end = clock.start + std::chrono::duration_cast<Clock::duration>(
                                std::chrono::duration<double>(options.duration));
  {
    std::optional<ProgressLine> progress;
    if (::isatty(STDERR_FILENO) == 1) progress.emplace(clock, answered, options.duration);
    std::thread enroller;
    if (enrollments) enroller = std::thread([&] { enrollments->Run(clock, enrolling); });
    std::thread memory_sampler;
    if (options.server_pid > 0) {
      memory_sampler = std::thread(
          [&] { SampleServerMemory(options.server_pid, clock, report.server_rss_samples); });
    }
    if (options.closed_loop) {
      std::this_thread::sleep_until(clock.start);
      for (auto& session : sessions) session->SendFrame(0, Clock::now());
    } else {
      SendOnSchedule(sessions, options.rate, clock);
    }
    std::this_thread::sleep_until(clock.end);
    for (auto& session : sessions) session->CloseWrites();
    // The updates of frames sent are awaited for kDrainTime at most.
    const Clock::time_point drained = clock.end + kDrainTime;
    for (auto& session : sessions) {
      if (!session->WaitDone(drained)) session->Cancel();
    }
    for (auto& session : sessions) {
      while (!session->WaitDone(Clock::now() + std::chrono::seconds(1))) {
      }
    }
    if (enroller.joinable()) enroller.join();
    if (memory_sampler.joinable()) memory_sampler.join();
  }
  report.generator_cpu_seconds = OwnCpuSeconds() - cpu_at_start;
  if (options.server_pid > 0) report.server_end = SampleServer(options.server_pid);

  // The load lasts its duration, or until the last update when frames were answered late.
  Clock::time_point last_update = clock.end;
  for (const auto& session : sessions) session->AddTo(report, last_update);
  report.elapsed_seconds = std::chrono::duration<double>(last_update - clock.start).count();
  if (enrollments) {
    enrollments->Delete();
    enrollments->AddTo(report);
  }

  if (options.json) {
    std::cout << LoadReportJson(report).dump() << std::endl;
  } else {
    std::cout << LoadReportText(report) << std::flush;
  }
  return 0;
}

}  // namespace

void AddLoadtestCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<LoadtestOptions>();
  CLI::App* command = app.add_subcommand(
      "loadtest",
      "Load a server with recognition sessions and measure it, in the manner of ghz.\n"
      "--sessions N sessions each stream the views of a dataset's objects as a turntable shows\n"
      "them (the azimuth advancing one view per frame), as CEDD descriptors computed once\n"
      "before the load (or, with --image-frames, as the encoded image files).\n"
      "Open loop (--rate R): each session sends R frames/s on a fixed schedule, and a round\n"
      "trip counts from the time the frame was due, so a late send or a queue is measured, not\n"
      "hidden. Closed loop (--closed-loop): each session sends its next frame when the update\n"
      "of the previous one arrives (the server's --max-fps must allow it).\n"
      "Sessions are opened before the clock starts; after --duration no frame is sent, the\n"
      "updates still due are awaited for 10 s, and sessions still owing some are cancelled.\n"
      "Session options left out (--engine, --top-k, --window, ...) take the server's defaults.\n"
      "Reports round trips in ms (p50/p90/p99/max), frames/s, sessions opened and failed,\n"
      "errors by gRPC status name, the server's processing_time_us, with --server-pid its CPU\n"
      "per frame and memory, and this generator's own CPU; --json for one JSON object. A\n"
      "progress line goes to stderr on a terminal. Exit status: 0 when the load ran (errors\n"
      "are in the report), 1 when it could not run, 2 for bad flags.");
  AddNetworkOptions(*command, options->network, /*server_required=*/true);
  AddSessionFlags(*command, options->session);
  command->add_option("--sessions", options->sessions, "concurrent sessions")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command
      ->add_option("--connections", options->connections,
                   "TCP connections the sessions are spread over, round robin: 1 (the\n"
                   "default, as ghz) multiplexes every session on one connection; as many as\n"
                   "--sessions gives each session its own, as separate devices would. A server\n"
                   "opens at most its --max-streams-per-connection calls (" +
                       std::to_string(server::ConnectionLimits{}.max_streams_per_connection) +
                       " by default) on one\n"
                       "connection and holds the sessions beyond them until others end")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  CLI::Option_group* mode = command->add_option_group("mode", "give exactly one");
  mode->add_option("--rate", options->rate, "open loop: frames per second per session (no default)")
      ->check(CLI::Range(0.001, 100000.0));
  mode->add_flag("--closed-loop", options->closed_loop,
                 "closed loop: each session sends its next frame as soon as the previous\n"
                 "frame's update arrives");
  mode->require_option(1);
  command->add_option("--duration", options->duration, "seconds of load")
      ->check(CLI::Range(0.1, 86400.0))
      ->capture_default_str();
  command
      ->add_option("--layout", options->layout,
                   "dataset layout: coil100 (objN__A.png files in --data) or manifest\n"
                   "(a CSV file, --manifest)")
      ->check(CLI::IsMember({"coil100", "manifest"}))
      ->capture_default_str();
  command
      ->add_option("--data", options->data,
                   "folder of COIL-100 images (--layout coil100; the default is the shared\n"
                   "data as seen from the repository root)")
      ->capture_default_str();
  command->add_option("--manifest", options->manifest,
                      "CSV with columns path,object,azimuth[,elevation] (--layout manifest)");
  command->add_option("--objects", options->objects,
                      "objects whose views the sessions show, e.g. 1-20 (default: all); session\n"
                      "s shows object s mod count, starting at a view of its own");
  command->add_flag("--image-frames", options->image_frames,
                    "send each frame as its encoded image file for the server to describe,\n"
                    "instead of a descriptor (default: descriptors)");
  CLI::Option* enroll_every =
      command
          ->add_option("--enroll-every", options->enroll_every,
                       "during the load, start an enrollment of the dataset's first object (all\n"
                       "its views, e.g. 72 for COIL-100) every this many seconds; each one is\n"
                       "deleted after the load (default 0: none, or back to back with\n"
                       "--enroll-count; needs an admin token)")
          ->check(CLI::Range(0.0, 86400.0));
  command
      ->add_option("--enroll-count", options->enroll_count,
                   "enrollments to run during the load (default 0: none, or as many as fit\n"
                   "with --enroll-every)")
      ->check(CLI::Range(0, 100000));
  command
      ->add_flag("--delete-during", options->delete_during,
                 "delete each object enrolled during the load as soon as the next one is\n"
                 "enrolled, so that the model set gains and loses an object every\n"
                 "--enroll-every seconds while the sessions run (a soak's churn)")
      ->needs(enroll_every);
  command
      ->add_option("--server-pid", options->server_pid,
                   "process id of the server, on this machine: report its CPU time per frame\n"
                   "(from /proc/PID/stat) and its resident memory at start, every tenth of the\n"
                   "load, and end")
      ->check(CLI::Range(1, 1 << 30));
  command->add_flag("--json", options->json,
                    "print one JSON object: frames_per_second, rtt_ms {p50, p90, p99, max,\n"
                    "mean}, errors {STATUS: count}, sessions, frames, server, generator,\n"
                    "enrollments (docs/results/load.md)");
  command->callback([options, &exit_code] {
    if (options->connections > options->sessions) {
      throw CLI::ValidationError("--connections",
                                 "must be in 1..--sessions (" + std::to_string(options->sessions) +
                                     "), got " + std::to_string(options->connections));
    }
    const int per_connection =
        (options->sessions + options->connections - 1) / options->connections;
    const int server_default = server::ConnectionLimits{}.max_streams_per_connection;
    if (per_connection > server_default) {
      std::cerr << "orbit loadtest: warning: " << per_connection
                << " sessions on one connection; a server with the default "
                   "--max-streams-per-connection ("
                << server_default
                << ") holds those beyond it until others end, and their frames' round trips "
                   "count from when they were due: give --connections "
                << (options->sessions + server_default - 1) / server_default
                << " or more, or raise the server's limit" << std::endl;
    }
    exit_code = RunLoadtest(*options);
  });
}

}  // namespace orbit::cli
