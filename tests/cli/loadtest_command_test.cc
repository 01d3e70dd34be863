// orbit loadtest (cli/loadtest_command.cc, cli/load_session.cc) against real `orbit serve`
// processes holding COIL-100 objects, as an engineer runs it.
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::CoilDir;
using ::testing::HasSubstr;
using testing::RunOrbit;
using testing::ScratchDir;
using testing::ServerProcess;

// A model store holding COIL-100 objects 1 and 2 (72 views each), made with orbit import.
std::filesystem::path CoilStore(const ScratchDir& dir) {
  const std::filesystem::path db = dir / "models.db";
  const testing::CommandResult imported = RunOrbit(
      "import --db " + db.string() + " --layout coil100 --data " + CoilDir() + " --objects 1-2");
  EXPECT_EQ(imported.exit_code, 0) << imported.err;
  return db;
}

// `orbit loadtest --json` on `server` with `arguments`; its report.
nlohmann::json Loadtest(const ServerProcess& server, const std::string& arguments) {
  const testing::CommandResult run =
      RunOrbit("loadtest --json --server " + server.address() + " --data " + CoilDir() +
               " --objects 1-2 " + arguments);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  if (run.exit_code != 0) return nlohmann::json::object();
  return nlohmann::json::parse(run.out);
}

void ExpectOrderedRoundTrips(const nlohmann::json& rtt) {
  EXPECT_GT(rtt.at("p50").get<double>(), 0) << rtt;
  EXPECT_LE(rtt.at("p50").get<double>(), rtt.at("p90").get<double>()) << rtt;
  EXPECT_LE(rtt.at("p90").get<double>(), rtt.at("p99").get<double>()) << rtt;
  EXPECT_LE(rtt.at("p99").get<double>(), rtt.at("max").get<double>()) << rtt;
}

TEST(LoadtestCommandTest, OpenLoopAnswersEveryFrameOnScheduleWithoutErrors) {
  ScratchDir dir;
  ServerProcess server({.database = CoilStore(dir)});
  const nlohmann::json report = Loadtest(
      server, "--sessions 3 --rate 20 --duration 2 --server-pid " + std::to_string(server.pid()));
  // 3 sessions x 20 frames/s x 2 s, every frame answered.
  EXPECT_EQ(report.at("frames").at("sent"), 120) << report;
  EXPECT_EQ(report.at("frames").at("answered"), 120) << report;
  EXPECT_GT(report.at("frames_per_second").get<double>(), 0);
  ExpectOrderedRoundTrips(report.at("rtt_ms"));
  EXPECT_EQ(report.at("rtt_ms").at("count"), 120);
  EXPECT_EQ(report.at("errors"), nlohmann::json::object());
  EXPECT_EQ(report.at("sessions").at("opened"), 3);
  EXPECT_EQ(report.at("sessions").at("failed"), 0);
  EXPECT_EQ(report.at("config").at("engine"), "hmm");  // the server's default
  EXPECT_EQ(report.at("config").at("mode"), "open-loop");
  // The server's own figures: its processing times and, through its pid, CPU and memory.
  EXPECT_GT(report.at("server").at("processing_time_us").at("p50").get<double>(), 0);
  EXPECT_LE(report.at("server").at("processing_time_us").at("p50").get<double>(),
            report.at("server").at("processing_time_us").at("p99").get<double>());
  EXPECT_GE(report.at("server").at("cpu_seconds").get<double>(), 0);
  EXPECT_GT(report.at("server").at("rss_mb_start").get<double>(), 1);
  EXPECT_GT(report.at("server").at("rss_mb_end").get<double>(), 1);
  EXPECT_TRUE(report.at("generator").contains("cpu_us_per_frame"));
}

TEST(LoadtestCommandTest, ClosedLoopAndImageFramesRunTheChosenEngine) {
  ScratchDir dir;
  ServerProcess server({.database = CoilStore(dir), .extra_args = {"--max-fps", "100000"}});
  const nlohmann::json closed =
      Loadtest(server, "--sessions 2 --closed-loop --duration 1 --engine vci");
  EXPECT_EQ(closed.at("config").at("mode"), "closed-loop");
  EXPECT_EQ(closed.at("config").at("engine"), "vci");
  EXPECT_GT(closed.at("frames").at("answered").get<int>(), 2);
  EXPECT_EQ(closed.at("frames").at("answered"), closed.at("frames").at("sent"));
  EXPECT_EQ(closed.at("errors"), nlohmann::json::object());
  ExpectOrderedRoundTrips(closed.at("rtt_ms"));

  const nlohmann::json images =
      Loadtest(server, "--sessions 2 --rate 10 --duration 1 --image-frames");
  EXPECT_EQ(images.at("config").at("frames"), "image");
  EXPECT_EQ(images.at("frames").at("sent"), 20);
  EXPECT_EQ(images.at("frames").at("answered"), 20);
  EXPECT_EQ(images.at("errors"), nlohmann::json::object());
}

// Sessions spread over connections of their own, as separate devices' would be, get every
// frame answered too (each connection its own: tests/client/connection_test.cc).
TEST(LoadtestCommandTest, SessionsOnConnectionsOfTheirOwnAreAnsweredAlike) {
  ScratchDir dir;
  ServerProcess server({.database = CoilStore(dir)});
  const nlohmann::json report =
      Loadtest(server, "--sessions 3 --connections 3 --rate 20 --duration 1");
  EXPECT_EQ(report.at("config").at("connections"), 3) << report;
  EXPECT_EQ(report.at("frames").at("sent"), 60);
  EXPECT_EQ(report.at("frames").at("answered"), 60);
  EXPECT_EQ(report.at("sessions").at("opened"), 3);
  EXPECT_EQ(report.at("errors"), nlohmann::json::object());
}

// More sessions on one connection than a server opens by default: the run says so, for the
// sessions beyond it would wait and their frames count late, and says how to spread them.
TEST(LoadtestCommandTest, WarnsWhenOneConnectionCarriesMoreSessionsThanAServerOpens) {
  ScratchDir dir;
  ServerProcess server({.database = CoilStore(dir)});
  const std::string at = "loadtest --json --server " + server.address() + " --data " + CoilDir() +
                         " --objects 1-2 --rate 1 --duration 0.2 --sessions 101";
  const testing::CommandResult crowded = RunOrbit(at);
  EXPECT_EQ(crowded.exit_code, 0) << crowded.err;
  EXPECT_THAT(crowded.err,
              HasSubstr("warning: 101 sessions on one connection; a server with the default "
                        "--max-streams-per-connection (100) holds those beyond it"));
  EXPECT_THAT(crowded.err, HasSubstr("give --connections 2 or more"));
  const testing::CommandResult spread = RunOrbit(at + " --connections 2");
  EXPECT_EQ(spread.exit_code, 0) << spread.err;
  EXPECT_THAT(spread.err, ::testing::Not(HasSubstr("warning")));
}

TEST(LoadtestCommandTest, SessionsBeyondTheServersLimitAreCountedAsResourceExhausted) {
  ScratchDir dir;
  ServerProcess server({.database = CoilStore(dir), .extra_args = {"--max-sessions", "2"}});
  const nlohmann::json report = Loadtest(server, "--sessions 4 --rate 10 --duration 1");
  EXPECT_EQ(report.at("errors"), (nlohmann::json{{"RESOURCE_EXHAUSTED", 2}})) << report;
  EXPECT_EQ(report.at("sessions").at("opened"), 2);
  EXPECT_EQ(report.at("sessions").at("failed"), 2);
  // The two admitted sessions ran: 2 x 10 frames/s x 1 s.
  EXPECT_EQ(report.at("frames").at("answered"), 20);
}

TEST(LoadtestCommandTest, EnrollmentsDuringTheLoadAreTimedAndDeletedAfterwards) {
  ScratchDir dir;
  ServerProcess server({.database = CoilStore(dir)});
  const nlohmann::json report =
      Loadtest(server, "--sessions 2 --rate 10 --duration 2 --enroll-count 2");
  ASSERT_TRUE(report.contains("enrollments")) << report;
  EXPECT_EQ(report.at("enrollments").at("done"), 2);
  EXPECT_EQ(report.at("enrollments").at("deleted"), 2);
  EXPECT_EQ(report.at("enrollments").at("views"), 72);  // all of obj1's views
  EXPECT_GT(report.at("enrollments").at("latency_ms").at("p50").get<double>(), 0);
  EXPECT_EQ(report.at("errors"), nlohmann::json::object());
  EXPECT_EQ(report.at("frames").at("answered"), 40);

  // Only the two imported objects are left.
  const testing::CommandResult listed = RunOrbit("list --server " + server.address());
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  EXPECT_EQ(testing::OutputLines(listed.out).size(), 2u) << listed.out;
}

// The soak of docs/results/load.md, shortened: sessions at 10 frames/s while an object is
// enrolled every half second and the one before it deleted, so the model set changes about 20
// times under open sessions. Every frame must be answered, no session may fail, and the model
// set must end as it began.
TEST(LoadtestCommandTest, AShortSoakWithEnrollmentsAndDeletionsLosesNoUpdate) {
  ScratchDir dir;
  ServerProcess server({.database = CoilStore(dir)});
  const nlohmann::json report =
      Loadtest(server,
               "--sessions 24 --rate 10 --duration 5 --enroll-every 0.5 --delete-during "
               "--server-pid " +
                   std::to_string(server.pid()));
  EXPECT_EQ(report.at("errors"), nlohmann::json::object()) << report;
  EXPECT_EQ(report.at("frames").at("sent"), 1200) << report;  // 24 x 10 x 5
  EXPECT_EQ(report.at("frames").at("unanswered"), 0) << report;
  EXPECT_EQ(report.at("sessions").at("opened"), 24);
  EXPECT_EQ(report.at("sessions").at("failed"), 0);
  EXPECT_EQ(report.at("sessions").at("cancelled"), 0);
  ASSERT_TRUE(report.contains("enrollments")) << report;
  // 10 enrollments are due (at 0, 0.5, ..., 4.5 s); a slow machine may fit fewer.
  EXPECT_GE(report.at("enrollments").at("done").get<int>(), 5) << report;
  EXPECT_LE(report.at("enrollments").at("done").get<int>(), 10) << report;
  EXPECT_EQ(report.at("enrollments").at("deleted"), report.at("enrollments").at("done"));
  EXPECT_EQ(report.at("enrollments").at("deleted_during_load"), true);
  // The server's memory at the start, every tenth of the load and the end.
  ASSERT_EQ(report.at("server").at("rss_mb_samples").size(), 11u) << report;
  EXPECT_GT(report.at("server").at("rss_mb_samples")[10][1].get<double>(), 0);
  EXPECT_GE(report.at("rtt_ms").at("worst_session_p99").get<double>(),
            report.at("rtt_ms").at("p50").get<double>());

  const testing::CommandResult listed = RunOrbit("list --server " + server.address());
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  EXPECT_EQ(testing::OutputLines(listed.out).size(), 2u) << listed.out;
}

TEST(LoadtestCommandTest, BadFlagsExitWithStatusTwoAndSayWhy) {
  const std::string at = "loadtest --server 127.0.0.1:1 ";
  const testing::CommandResult neither = RunOrbit(at + "--sessions 2");
  EXPECT_EQ(neither.exit_code, 2);
  EXPECT_THAT(neither.err, HasSubstr("[--rate,--closed-loop]"));
  const testing::CommandResult both = RunOrbit(at + "--rate 5 --closed-loop");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_THAT(both.err, HasSubstr("2 were given"));
  const testing::CommandResult engine = RunOrbit(at + "--rate 5 --engine nope");
  EXPECT_EQ(engine.exit_code, 2);
  EXPECT_THAT(engine.err, HasSubstr("--engine: nope not in {vci,hmm,"));
  EXPECT_EQ(RunOrbit(at + "--rate 0").exit_code, 2);
  EXPECT_EQ(RunOrbit(at + "--rate 5 --sessions 0").exit_code, 2);
  EXPECT_EQ(RunOrbit(at + "--rate 5 --frobnicate").exit_code, 2);
  const testing::CommandResult connections = RunOrbit(at + "--rate 5 --sessions 2 --connections 3");
  EXPECT_EQ(connections.exit_code, 2);
  EXPECT_THAT(connections.err, HasSubstr("--connections: must be in 1..--sessions (2), got 3"));
  const testing::CommandResult churn = RunOrbit(at + "--rate 5 --delete-during");
  EXPECT_EQ(churn.exit_code, 2);
  EXPECT_THAT(churn.err, HasSubstr("--delete-during requires --enroll-every"));
  // A server that is not there is not a bad flag: the command ran and failed.
  const testing::CommandResult unreachable = RunOrbit(at + "--rate 5 --timeout 1");
  EXPECT_EQ(unreachable.exit_code, 1);
  EXPECT_THAT(unreachable.err, HasSubstr("orbit loadtest: cannot reach a server at "));

  const testing::CommandResult help = RunOrbit("loadtest --help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* text :
       {"frames per second per session", "seconds of load", "concurrent sessions", "--connections",
        "--enroll-every", "--server-pid", "in ms"}) {
    EXPECT_THAT(help.out, HasSubstr(text));
  }
}

}  // namespace
}  // namespace orbit
