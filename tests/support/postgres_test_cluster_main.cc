// orbit_test_postgres start|stop FOLDER: ctest's fixture orbit_postgres (tests/CMakeLists.txt),
// one PostgreSQL server for every *Postgres* test of a run (tests/support/postgres_test_cluster.h).
#include <exception>
#include <iostream>
#include <string>

#include "tests/support/postgres_test_cluster.h"

int main(int argc, char** argv) {
  const std::string command = argc == 3 ? argv[1] : "";
  if (command != "start" && command != "stop") {
    std::cerr << "usage: orbit_test_postgres start|stop FOLDER\n";
    return 2;
  }
  try {
    if (command == "start") {
      orbit::testing::PostgresTestCluster::Start(argv[2]);
      std::cout << "PostgreSQL 15 listening on a unix socket in " << argv[2] << "\n";
    } else {
      orbit::testing::PostgresTestCluster::Stop(argv[2]);
    }
  } catch (const std::exception& e) {
    std::cerr << "orbit_test_postgres " << command << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
