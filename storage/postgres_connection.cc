#include "storage/postgres_connection.h"

#include <poll.h>

#include <algorithm>
#include <charconv>
#include <stdexcept>
#include <system_error>

#include "storage/postgres_error.h"
#include "storage/store_error.h"

namespace orbit {
namespace {

// libpq's messages end in a newline.
std::string Trimmed(const char* message) {
  std::string text = message != nullptr ? message : "";
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

template <typename Number>
Number ParseNumber(std::string_view text, std::string_view what) {
  Number value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    throw StoreError(StoreError::Code::kCorrupt,
                     "the server sent \"" + std::string(text) + "\" for " + std::string(what));
  }
  return value;
}

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Ignores the server's notices ("relation already exists, skipping", ...): libpq would print
// them on stderr.
void IgnoreNotice(void*, const char*) {}

}  // namespace

std::string RedactedTarget(const std::string& conninfo) {
  char* error = nullptr;
  PQconninfoOption* options = PQconninfoParse(conninfo.c_str(), &error);
  if (options == nullptr) {
    const std::string reason = error != nullptr ? Trimmed(error) : "out of memory";
    PQfreemem(error);
    throw std::invalid_argument("invalid PostgreSQL connection string: " + reason);
  }
  std::string target;
  for (const PQconninfoOption* option = options; option->keyword != nullptr; ++option) {
    const std::string_view keyword = option->keyword;
    if (option->val == nullptr || keyword == "password" || keyword == "sslpassword") continue;
    if (!target.empty()) target += ' ';
    target += keyword;
    target += '=';
    target += option->val;
  }
  PQconninfoFree(options);
  return target;
}

PostgresParams& PostgresParams::Add(std::int64_t value) {
  values_.push_back(std::to_string(value));
  null_.push_back(false);
  binary_.push_back(0);
  return *this;
}

PostgresParams& PostgresParams::Add(double value) {
  char text[32];
  const auto [end, error] = std::to_chars(text, text + sizeof text, value);
  values_.emplace_back(text, error == std::errc() ? end : text);
  null_.push_back(false);
  binary_.push_back(0);
  return *this;
}

PostgresParams& PostgresParams::Add(std::string_view text) {
  values_.emplace_back(text);
  null_.push_back(false);
  binary_.push_back(0);
  return *this;
}

PostgresParams& PostgresParams::AddBytes(std::span<const std::uint8_t> bytes) {
  values_.emplace_back(bytes.begin(), bytes.end());
  null_.push_back(false);
  binary_.push_back(1);
  return *this;
}

PostgresParams& PostgresParams::AddNull() {
  values_.emplace_back();
  null_.push_back(true);
  binary_.push_back(0);
  return *this;
}

std::string PostgresResult::Text(int row, int column) const {
  return std::string(PQgetvalue(result_.get(), row, column),
                     PQgetlength(result_.get(), row, column));
}

std::int64_t PostgresResult::Int64(int row, int column) const {
  return ParseNumber<std::int64_t>(Text(row, column), PQfname(result_.get(), column));
}

double PostgresResult::Double(int row, int column) const {
  return ParseNumber<double>(Text(row, column), PQfname(result_.get(), column));
}

std::string PostgresResult::Bytes(int row, int column) const {
  if (IsNull(row, column)) return {};
  const std::string_view hex(PQgetvalue(result_.get(), row, column),
                             PQgetlength(result_.get(), row, column));
  if (hex.size() < 2 || hex.substr(0, 2) != "\\x" || hex.size() % 2 != 0) {
    throw StoreError(StoreError::Code::kInternal,
                     std::string("the server sent bytea in an unexpected form for ") +
                         PQfname(result_.get(), column) + " (bytea_output must be hex)");
  }
  std::string bytes;
  bytes.reserve(hex.size() / 2 - 1);
  for (std::size_t i = 2; i < hex.size(); i += 2) {
    const int high = HexDigit(hex[i]);
    const int low = HexDigit(hex[i + 1]);
    if (high < 0 || low < 0) {
      throw StoreError(StoreError::Code::kCorrupt,
                       std::string("invalid hex in bytea ") + PQfname(result_.get(), column));
    }
    bytes.push_back(static_cast<char>(high * 16 + low));
  }
  return bytes;
}

PostgresConnection::PostgresConnection(const std::string& conninfo, std::int64_t lock_timeout_ms)
    : target_(RedactedTarget(conninfo)) {
  // expand_dbname: `conninfo` is a whole connection string; "orbit" names the connections in
  // pg_stat_activity unless the string sets application_name.
  const char* keywords[] = {"dbname", "fallback_application_name", nullptr};
  const char* values[] = {conninfo.c_str(), "orbit", nullptr};
  connection_ = PQconnectdbParams(keywords, values, /*expand_dbname=*/1);
  if (connection_ == nullptr || PQstatus(connection_) != CONNECTION_OK) {
    const std::string reason =
        connection_ != nullptr ? Trimmed(PQerrorMessage(connection_)) : "out of memory";
    PQfinish(connection_);
    throw StoreError(StoreError::Code::kIo,
                     "cannot connect to PostgreSQL " + target_ + ": " + reason);
  }
  PQsetNoticeProcessor(connection_, &IgnoreNotice, nullptr);
  try {
    // Timestamps and bytea in the forms the store parses, whatever the server's defaults.
    Execute("SET bytea_output = 'hex'; SET lock_timeout = " + std::to_string(lock_timeout_ms));
  } catch (...) {
    PQfinish(connection_);
    throw;
  }
}

PostgresConnection::~PostgresConnection() { PQfinish(connection_); }

PostgresResult PostgresConnection::Check(PGresult* raw, std::string_view sql) {
  PostgresResult result(raw);
  const ExecStatusType status = PQresultStatus(raw);
  if (raw != nullptr && (status == PGRES_COMMAND_OK || status == PGRES_TUPLES_OK)) return result;
  const char* sqlstate = raw != nullptr ? PQresultErrorField(raw, PG_DIAG_SQLSTATE) : nullptr;
  const std::string message = raw != nullptr && PQresultErrorMessage(raw)[0] != '\0'
                                  ? PQresultErrorMessage(raw)
                                  : PQerrorMessage(connection_);
  // The statement's start names it well enough (a view insert has thousands of placeholders).
  std::string_view start = sql.substr(sql.find_first_not_of(" \n"));
  start = start.substr(0, std::min({start.find('\n'), start.find(" ("), std::size_t{60}}));
  if (PQstatus(connection_) != CONNECTION_OK) {
    throw PostgresError("", message, "lost the connection to PostgreSQL " + target_);
  }
  throw PostgresError(sqlstate != nullptr ? sqlstate : "", message,
                      "PostgreSQL refused `" + std::string(start) + "`");
}

void PostgresConnection::Execute(const std::string& sql) {
  Check(PQexec(connection_, sql.c_str()), sql);
}

PostgresResult PostgresConnection::Query(const std::string& sql, const PostgresParams& params) {
  std::vector<const char*> values(params.values_.size());
  std::vector<int> lengths(params.values_.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    values[i] = params.null_[i] ? nullptr : params.values_[i].data();
    lengths[i] = static_cast<int>(params.values_[i].size());
  }
  return Check(PQexecParams(connection_, sql.c_str(), params.size(), /*paramTypes=*/nullptr,
                            values.data(), lengths.data(), params.binary_.data(),
                            /*resultFormat=*/0),
               sql);
}

bool PostgresConnection::Reusable() const {
  return PQstatus(connection_) == CONNECTION_OK && PQtransactionStatus(connection_) == PQTRANS_IDLE;
}

bool PostgresConnection::InTransaction() const {
  const PGTransactionStatusType status = PQtransactionStatus(connection_);
  return status == PQTRANS_INTRANS || status == PQTRANS_INERROR || status == PQTRANS_ACTIVE;
}

bool PostgresConnection::Lost() const { return PQstatus(connection_) != CONNECTION_OK; }

bool PostgresConnection::StillOpen() {
  if (PQstatus(connection_) != CONNECTION_OK) return false;
  // An idle session is sent nothing (the store never LISTENs on its connections) until the
  // server ends it: then a FATAL message and the end of the stream wait on the socket.
  pollfd socket{.fd = PQsocket(connection_), .events = POLLIN, .revents = 0};
  return ::poll(&socket, 1, 0) == 0;
}

std::vector<std::string> PostgresConnection::TakeNotifications() {
  if (PQconsumeInput(connection_) == 0 || PQstatus(connection_) != CONNECTION_OK) {
    throw StoreError(StoreError::Code::kIo, "lost the connection to PostgreSQL " + target_ + ": " +
                                                Trimmed(PQerrorMessage(connection_)));
  }
  std::vector<std::string> payloads;
  while (PGnotify* notify = PQnotifies(connection_)) {
    payloads.emplace_back(notify->extra);
    PQfreemem(notify);
  }
  return payloads;
}

}  // namespace orbit
