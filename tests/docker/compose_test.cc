// docker/docker-compose.replicas.yml and docker/haproxy.cfg agree: the balancer is given an
// address for every replica slot the configuration has, each names a replica service of the
// compose file on the port the server image listens on, and every replica uses the compose
// file's PostgreSQL service. (No Docker engine here: the compose file's parts run on loopback
// in tests/docker/replicas_test.cc.)
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace orbit {
namespace {

std::string SourceFile(const std::string& path) {
  std::ifstream in(std::string(ORBIT_SOURCE_DIR) + "/" + path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every first capture of `pattern` in `text`.
std::set<std::string> Captures(const std::string& text, const std::string& pattern) {
  std::set<std::string> found;
  const std::regex re(pattern);
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator();
       ++it) {
    found.insert((*it)[1]);
  }
  return found;
}

TEST(ReplicasComposeTest, TheBalancerReachesEveryReplicaOfTheComposeFile) {
  const std::string compose = SourceFile("docker/docker-compose.replicas.yml");
  const std::string haproxy = SourceFile("docker/haproxy.cfg");
  const std::string image = SourceFile("docker/Dockerfile");
  ASSERT_FALSE(compose.empty());
  ASSERT_FALSE(haproxy.empty());

  const std::set<std::string> slots = Captures(haproxy, R"(server \S+ "\$\{(ORBIT_REPLICA_\d)\}")");
  EXPECT_EQ(slots,
            (std::set<std::string>{"ORBIT_REPLICA_1", "ORBIT_REPLICA_2", "ORBIT_REPLICA_3"}));
  const std::set<std::string> services =
      Captures(compose, R"(\n  (replica-\d+):\n    <<: \*replica)");
  EXPECT_EQ(services.size(), 3u);

  std::smatch port;
  ASSERT_TRUE(std::regex_search(image, port, std::regex(R"(ORBIT_LISTEN=0\.0\.0\.0:(\d+))")));
  for (const std::string& slot : slots) {
    std::smatch target;
    ASSERT_TRUE(std::regex_search(compose, target, std::regex(slot + R"(: (\S+):(\d+))")))
        << slot << " is not set by the compose file";
    EXPECT_TRUE(services.count(target[1])) << target[1] << " is not a replica service";
    EXPECT_EQ(target[2], port[1]) << slot;
  }
  EXPECT_NE(compose.find("ORBIT_BALANCER_LISTEN: 0.0.0.0:"), std::string::npos);
  EXPECT_NE(haproxy.find("\"${ORBIT_BALANCER_LISTEN}\""), std::string::npos);

  // The replicas share the compose file's PostgreSQL, and not the image's SQLite default.
  EXPECT_NE(compose.find("\n  postgres:\n"), std::string::npos);
  EXPECT_TRUE(std::regex_search(compose,
                                std::regex(R"(ORBIT_STORE: postgresql://[^@\n]+@postgres:5432/)")));
  EXPECT_NE(compose.find("ORBIT_DB: \"\""), std::string::npos);
}

}  // namespace
}  // namespace orbit
