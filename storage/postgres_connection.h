// PostgresConnection: one open libpq connection to a PostgreSQL server, with the typed
// parameters and results the PostgreSQL model store needs.
//
// Values travel as text, except bytea parameters, which are sent in binary (no escaping). Doubles
// are written with std::to_chars' shortest round-trip form and PostgreSQL (12+) prints them the
// same way, so a stored double reads back bit for bit.
//
// Not thread-safe: a connection is used by one thread at a time (PostgresModelStore lends each
// call a connection of its own from a small pool).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <libpq-fe.h>

namespace orbit {

// The connection target of `conninfo` (a postgresql:// URI or "key=value ..." text) as it may be
// shown to an operator: every parameter given, in libpq's "key=value" form, without the password.
// Throws std::invalid_argument with libpq's reason when libpq cannot parse `conninfo`.
std::string RedactedTarget(const std::string& conninfo);

// The parameters of one statement, $1, $2, ... in the order added.
class PostgresParams {
 public:
  PostgresParams& Add(std::int64_t value);
  PostgresParams& Add(double value);
  PostgresParams& Add(std::string_view text);
  PostgresParams& AddBytes(std::span<const std::uint8_t> bytes);  // a bytea, sent in binary
  PostgresParams& AddNull();

  int size() const { return static_cast<int>(values_.size()); }

 private:
  friend class PostgresConnection;
  std::vector<std::string> values_;
  std::vector<bool> null_;
  std::vector<int> binary_;  // libpq's paramFormats: 1 binary, 0 text
};

// The rows of a statement that succeeded, read by row and column (both from 0).
class PostgresResult {
 public:
  explicit PostgresResult(PGresult* result) : result_(result, &PQclear) {}

  int rows() const { return PQntuples(result_.get()); }
  bool IsNull(int row, int column) const { return PQgetisnull(result_.get(), row, column) != 0; }
  std::string Text(int row, int column) const;
  std::int64_t Int64(int row, int column) const;
  double Double(int row, int column) const;
  // A bytea column (PostgreSQL's hex output, decoded); "" for NULL.
  std::string Bytes(int row, int column) const;

 private:
  std::unique_ptr<PGresult, decltype(&PQclear)> result_;
};

class PostgresConnection {
 public:
  // Connects to `conninfo`; the session then waits at most `lock_timeout_ms` for any lock
  // (0: for ever). Throws StoreError kIo "cannot connect to PostgreSQL <target>: <libpq's
  // reason>" (target as RedactedTarget) when the server is unreachable or refuses the
  // connection, std::invalid_argument when `conninfo` cannot be parsed.
  PostgresConnection(const std::string& conninfo, std::int64_t lock_timeout_ms);
  ~PostgresConnection();

  PostgresConnection(const PostgresConnection&) = delete;
  PostgresConnection& operator=(const PostgresConnection&) = delete;

  // Runs fixed SQL text: one or more statements without parameters (schema changes, BEGIN,
  // COMMIT). Never pass text built from input: values go through Query's parameters.
  void Execute(const std::string& sql);

  // Runs one statement with its parameters and returns its rows. Throws StoreError
  // (storage/postgres_error.h) when the server refuses it or the connection is lost.
  PostgresResult Query(const std::string& sql, const PostgresParams& params = {});

  // True while the connection is up and outside any transaction: fit to be lent again.
  bool Reusable() const;
  // True inside a transaction block (open or failed).
  bool InTransaction() const;
  // True once the link to the server is known to be down.
  bool Lost() const;
  // False when the server sent anything while the connection was idle, which for the store's
  // connections means it ended the session (a restart, pg_terminate_backend): a pooled
  // connection is checked before it is lent. Does not wait.
  bool StillOpen();

  // The connection's socket, to wait on with poll() for notifications (LISTEN).
  int Socket() const { return PQsocket(connection_); }
  // Reads what the server sent without waiting and returns the payloads of the notifications
  // received on any channel LISTENed to, oldest first (empty when none). Throws StoreError kIo
  // "lost the connection to PostgreSQL <target>" when the server closed the connection.
  std::vector<std::string> TakeNotifications();

  // The redacted connection target, for messages.
  const std::string& target() const { return target_; }

 private:
  PostgresResult Check(PGresult* result, std::string_view sql);

  std::string target_;
  PGconn* connection_ = nullptr;
};

}  // namespace orbit
