// The networked subcommands of `orbit` (enroll, recognize, info, demo) against a real
// `orbit serve` process, as a user would type them.
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "client/connection.h"
#include "client/models_client.h"
#include "storage/sqlite_model_store.h"
#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::CoilFile;
using testing::OrbitBinary;
using testing::OutputLines;
using testing::RunCommand;
using testing::ServerProcess;

// `--image F --azimuth A` for object `object` at the given azimuths, reported `offset` off.
std::string Frames(int object, const std::vector<int>& azimuths, int offset = 0) {
  std::string args;
  for (int a : azimuths) {
    args += " --image " + CoilFile(object, a) + " --azimuth " + std::to_string(a + offset);
  }
  return args;
}

std::vector<int> EveryTwentyDegrees() {
  std::vector<int> azimuths;
  for (int a = 0; a < 360; a += 20) azimuths.push_back(a);
  return azimuths;
}

TEST(CliNetwork, EnrollsThenRecognisesWithJsonAndTextOutput) {
  ServerProcess server;
  const std::string orbit = OrbitBinary() + " ";
  const std::string at = " --server " + server.address();
  for (int object = 1; object <= 3; ++object) {
    const auto r = RunCommand(orbit + "enroll" + at + " --name obj" + std::to_string(object) +
                              Frames(object, EveryTwentyDegrees()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "enrolled obj" + std::to_string(object) + " (id " + std::to_string(object) +
                         ", 18 views)\n");
  }
  const auto again = RunCommand(orbit + "enroll" + at + " --name obj1" + Frames(1, {0, 20}));
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("ALREADY_EXISTS"), std::string::npos) << again.err;

  const auto info = RunCommand(orbit + "info --json" + at);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto info_json = nlohmann::json::parse(info.out);
  EXPECT_EQ(info_json["objects"], 3);
  EXPECT_EQ(info_json["views"], 54);
  EXPECT_EQ(info_json["variant"], "cedd-lire");

  // Object 2 between its enrolled views, the compass 90 degrees off.
  const std::string frames = Frames(2, {30, 50, 70, 90}, 90);
  const auto json = RunCommand(orbit + "recognize --json --top-k 2" + at + frames);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const std::vector<std::string> lines = OutputLines(json.out);
  ASSERT_EQ(lines.size(), 4u) << json.out;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const auto update = nlohmann::json::parse(lines[k]);
    EXPECT_EQ(update["frame"], k);
    EXPECT_TRUE(update["decision"] == "ACCEPT" || update["decision"] == "UNKNOWN" ||
                update["decision"] == "UNDECIDED")
        << lines[k];
    EXPECT_TRUE(update["move"] == "LEFT" || update["move"] == "RIGHT" || update["move"] == "NONE")
        << lines[k];
    const auto& candidates = update["candidates"];
    ASSERT_TRUE(candidates.is_array());
    ASSERT_GE(candidates.size(), 1u);
    ASSERT_LE(candidates.size(), 2u);
    for (std::size_t i = 1; i < candidates.size(); ++i) {
      EXPECT_GE(candidates[i - 1]["score"].get<double>(), candidates[i]["score"].get<double>());
    }
    EXPECT_TRUE(candidates[0].contains("id"));
  }
  const auto last = nlohmann::json::parse(lines.back());
  EXPECT_EQ(last["candidates"][0]["name"], "obj2");
  EXPECT_EQ(last["candidates"][0]["id"], 2);
  EXPECT_EQ(last["decision"], "ACCEPT");

  const auto text = RunCommand(orbit + "recognize" + at + frames);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const std::vector<std::string> text_lines = OutputLines(text.out);
  ASSERT_EQ(text_lines.size(), 4u);
  EXPECT_EQ(text_lines[3].rfind("frame 3  ACCEPT     move ", 0), 0u) << text_lines[3];
  EXPECT_NE(text_lines[3].find(" obj2 (id 2) "), std::string::npos) << text_lines[3];
}

TEST(CliNetwork, ReportsUnreachableServersAndBadArguments) {
  const std::string orbit = OrbitBinary() + " ";
  ServerProcess server;
  const std::string address = server.address();
  ASSERT_EQ(server.Stop(SIGTERM), 0);
  const auto down = RunCommand(orbit + "info --timeout 2 --server " + address);
  EXPECT_EQ(down.exit_code, 1);
  EXPECT_NE(down.err.find("ServerInfo: UNAVAILABLE"), std::string::npos) << down.err;

  const auto unpaired = RunCommand(orbit + "recognize --server " + address + " --image " +
                                   CoilFile(1, 0) + " --azimuth 0 --azimuth 5");
  EXPECT_EQ(unpaired.exit_code, 1);
  EXPECT_NE(unpaired.err.find("one --azimuth per --image (1 images, 2 azimuths)"),
            std::string::npos)
      << unpaired.err;
}

TEST(CliNetwork, DemoEnrollsItsObjectsOnceAndRecognisesTheOneItCircles) {
  ServerProcess server;
  const std::string demo = OrbitBinary() + " demo --json --server " + server.address();
  const auto first = RunCommand(demo);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("demo-box: enrolled (id 1, 36 views"), std::string::npos) << first.out;
  EXPECT_NE(first.out.find("demo-crate: enrolled (id 3, 36 views"), std::string::npos);
  std::vector<nlohmann::json> updates;
  for (const std::string& line : OutputLines(first.out)) {
    if (!line.empty() && line[0] == '{') updates.push_back(nlohmann::json::parse(line));
  }
  ASSERT_EQ(updates.size(), 8u) << first.out;
  EXPECT_EQ(updates.back()["frame"], 7);
  EXPECT_EQ(updates.back()["candidates"][0]["name"], "demo-can");

  const auto second = RunCommand(demo + " --object demo-crate --frames 3");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.out.find("demo-can: already enrolled (id 2, 36 views)"), std::string::npos)
      << second.out;
  const std::vector<std::string> lines = OutputLines(second.out);
  std::string last_update;
  for (const std::string& line : lines) {
    if (!line.empty() && line[0] == '{') last_update = line;
  }
  ASSERT_FALSE(last_update.empty()) << second.out;
  EXPECT_EQ(nlohmann::json::parse(last_update)["candidates"][0]["name"], "demo-crate");
}

TEST(CliNetwork, TokensAndTlsFromTheCommandLine) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("orbit_cli_tls_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream tokens(dir / "tokens");
    tokens << "admin-token-0123456 admin\nreader-token-0123456 recognize\n";
    std::ofstream reader(dir / "reader.token");
    reader << "reader-token-0123456\n";
  }
  const std::string make_cert =
      "openssl req -x509 -newkey rsa:2048 -nodes -days 2 -subj /CN=edge.test "
      "-addext subjectAltName=DNS:edge.test -keyout " + (dir / "key.pem").string() +
      " -out " + (dir / "cert.pem").string() + " 2>/dev/null";
  ASSERT_EQ(std::system(make_cert.c_str()), 0) << "openssl could not make a test certificate";
  testing::ServerProcessOptions options;
  options.tokens_file = dir / "tokens";
  options.tls_cert = dir / "cert.pem";
  options.tls_key = dir / "key.pem";
  ServerProcess server(options);
  const std::string net = " --server " + server.address() + " --tls-ca " +
                          (dir / "cert.pem").string() + " --tls-server-name edge.test";
  const std::string orbit = OrbitBinary() + " ";
  const std::string reader_file = " --token-file " + (dir / "reader.token").string();

  const auto enrolled = RunCommand(orbit + "enroll" + net + " --token admin-token-0123456" +
                                   " --name obj1" + Frames(1, EveryTwentyDegrees()));
  ASSERT_EQ(enrolled.exit_code, 0) << enrolled.err;
  const auto denied =
      RunCommand(orbit + "enroll" + net + reader_file + " --name obj2" + Frames(2, {0, 20}));
  EXPECT_EQ(denied.exit_code, 1);
  EXPECT_NE(denied.err.find("PERMISSION_DENIED"), std::string::npos) << denied.err;
  const auto anonymous = RunCommand("env -u ORBIT_TOKEN " + orbit + "info" + net);
  EXPECT_EQ(anonymous.exit_code, 1);
  EXPECT_NE(anonymous.err.find("UNAUTHENTICATED"), std::string::npos) << anonymous.err;

  // The token from the environment; a token file on the command line wins over it.
  EXPECT_EQ(RunCommand("ORBIT_TOKEN=reader-token-0123456 " + orbit + "info" + net).exit_code, 0);
  const auto file_wins =
      RunCommand("ORBIT_TOKEN=stale-token-000000000 " + orbit + "list" + net + reader_file);
  ASSERT_EQ(file_wins.exit_code, 0) << file_wins.err;
  EXPECT_EQ(file_wins.out.rfind("1 obj1 cedd-lire 18 ", 0), 0u) << file_wins.out;
  const auto recognised = RunCommand(orbit + "recognize --json" + net + reader_file +
                                     Frames(1, {30, 50}));
  ASSERT_EQ(recognised.exit_code, 0) << recognised.err;
  EXPECT_EQ(nlohmann::json::parse(OutputLines(recognised.out).back())["candidates"][0]["name"],
            "obj1");

  // Plaintext against the TLS port fails.
  EXPECT_NE(RunCommand(orbit + "info --timeout 3 --server " + server.address() + reader_file)
                .exit_code,
            0);
  std::filesystem::remove_all(dir);
}

// Every line of `orbit list` without its last column (updated_at).
std::vector<std::string> WithoutTimestamps(const std::string& listing) {
  std::vector<std::string> lines = OutputLines(listing);
  for (std::string& line : lines) line = line.substr(0, line.rfind(' '));
  return lines;
}

TEST(CliNetwork, ImportListAndDeleteWorkOnAServerAsOnAFile) {
  ServerProcess server;
  const std::string orbit = OrbitBinary() + " ";
  const std::string at = " --server " + server.address();
  const std::string coil = " --layout coil100 --data " + (testing::DataDir() / "coil-100").string();
  const auto imported = RunCommand(orbit + "import" + at + coil + " --objects 1-2");
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_EQ(OutputLines(imported.out),
            (std::vector<std::string>{"enrolled obj1 (id 1, 72 views)",
                                      "enrolled obj2 (id 2, 72 views)"}));
  EXPECT_NE(imported.err.find("2 objects enrolled, 0 already present, on " + server.address()),
            std::string::npos)
      << imported.err;
  const auto resumed = RunCommand(orbit + "import" + at + coil + " --objects 1-3");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(OutputLines(resumed.out),
            (std::vector<std::string>{"skipped obj1 (already on the server as id 1)",
                                      "skipped obj2 (already on the server as id 2)",
                                      "enrolled obj3 (id 3, 72 views)"}));

  // The same import into a file stores the very same views (same descriptors, same seeded
  // typical distances), and both list alike.
  const auto dir = std::filesystem::temp_directory_path() /
                   ("orbit_cli_network_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string db = (dir / "models.db").string();
  ASSERT_EQ(RunCommand(orbit + "import --db " + db + coil + " --objects 1-3").exit_code, 0);
  {
    SqliteModelStore store(db);
    const std::optional<StoredObject> local = store.Get(2);
    ASSERT_TRUE(local.has_value());
    const Connection connection(testing::At(server.address()));
    const v1::GetObjectResponse remote = ModelsClient(connection).GetObject(ObjectById(2), true);
    ASSERT_EQ(remote.views_size(), static_cast<int>(local->views.size()));
    for (int f = 0; f < remote.views_size(); ++f) {
      const ModelView& view = local->views[f];
      const std::string cedd(view.descriptor.begin(), view.descriptor.end());
      EXPECT_EQ(remote.views(f).cedd(), cedd);
      EXPECT_EQ(remote.views(f).azimuth_deg(), view.azimuth);
      EXPECT_DOUBLE_EQ(remote.views(f).typical_distance(), view.typical_distance);
    }
  }
  const auto listed_remote = RunCommand(orbit + "list" + at);
  const auto listed_local = RunCommand(orbit + "list --db " + db);
  ASSERT_EQ(listed_remote.exit_code, 0) << listed_remote.err;
  EXPECT_EQ(WithoutTimestamps(listed_remote.out), WithoutTimestamps(listed_local.out));
  EXPECT_EQ(WithoutTimestamps(listed_remote.out)[2], "3 obj3 cedd-lire 72");
  const auto json = RunCommand(orbit + "list --json" + at);
  ASSERT_EQ(OutputLines(json.out).size(), 3u);
  EXPECT_EQ(nlohmann::json::parse(OutputLines(json.out)[0])["name"], "obj1");

  const auto deleted = RunCommand(orbit + "delete" + at + " obj2");
  ASSERT_EQ(deleted.exit_code, 0) << deleted.err;
  EXPECT_EQ(deleted.out, "deleted obj2 (id 2, 72 views)\n");
  const auto missing = RunCommand(orbit + "delete" + at + " obj2");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("no object named \"obj2\" on " + server.address()),
            std::string::npos)
      << missing.err;
  EXPECT_EQ(OutputLines(RunCommand(orbit + "list" + at).out).size(), 2u);

  // One of --db and --server, and the server's variant.
  const auto neither = RunCommand(orbit + "list");
  EXPECT_EQ(neither.exit_code, 1);
  EXPECT_NE(neither.err.find("give --db FILE (a local model store) or --server HOST:PORT"),
            std::string::npos)
      << neither.err;
  EXPECT_NE(RunCommand(orbit + "list --db " + db + at).exit_code, 0);
  const auto variant =
      RunCommand(orbit + "import" + at + coil + " --objects 4 --variant cedd-full");
  EXPECT_EQ(variant.exit_code, 1);
  EXPECT_NE(variant.err.find("--variant cedd-full is not the server's (cedd-lire)"),
            std::string::npos)
      << variant.err;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace orbit
