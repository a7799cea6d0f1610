#include "diagnostics/monitor/sqlite.hpp"

#include <sqlite3.h>

#include "core/error.hpp"

namespace ambid::diag::sqlite {

Connection::Connection(const std::string& path, bool read_only) : path_(path) {
  const int flags = read_only ? SQLITE_OPEN_READONLY : (SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  const int rc = sqlite3_open_v2(path.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close_v2(db_);
    db_ = nullptr;
    throw Error("trend store " + path + ": open: " + message + " (code " + std::to_string(rc) + ")");
  }
  sqlite3_extended_result_codes(db_, 1);
}

Connection::~Connection() { sqlite3_close_v2(db_); }

void Connection::fail(int code, std::string_view operation) const {
  throw Error("trend store " + path_ + ": " + std::string(operation) + ": " + sqlite3_errmsg(db_) + " (code " +
              std::to_string(code) + ")");
}

void Connection::check(int code, std::string_view operation) const {
  if (code != SQLITE_OK) fail(code, operation);
}

void Connection::set_busy_timeout(int milliseconds) {
  check(sqlite3_busy_timeout(db_, milliseconds), "set busy timeout");
}

std::int64_t Connection::changes() const { return sqlite3_changes64(db_); }

void Connection::exec(std::string_view sql, std::string_view operation) {
  check(sqlite3_exec(db_, std::string(sql).c_str(), nullptr, nullptr, nullptr), operation);
}

std::string Connection::query_text(std::string_view sql, std::string_view operation) {
  Statement statement(*this, sql, operation);
  auto run = statement.run();
  if (!run.step()) throw Error("trend store " + path_ + ": " + std::string(operation) + ": no result row");
  return run.column_text(0);
}

std::int64_t Connection::query_int(std::string_view sql, std::string_view operation) {
  Statement statement(*this, sql, operation);
  auto run = statement.run();
  if (!run.step()) throw Error("trend store " + path_ + ": " + std::string(operation) + ": no result row");
  return run.column_int(0);
}

Statement::Statement(Connection& db, std::string_view sql, std::string_view operation)
    : db_(db), operation_(operation) {
  db_.check(sqlite3_prepare_v3(db_.handle(), sql.data(), static_cast<int>(sql.size()), SQLITE_PREPARE_PERSISTENT,
                               &stmt_, nullptr),
            "prepare " + operation_);
}

Statement::~Statement() { sqlite3_finalize(stmt_); }

Statement::Run::~Run() {
  // The error of a failed step was thrown already; reset returns it again.
  sqlite3_reset(s_.stmt_);
  sqlite3_clear_bindings(s_.stmt_);
}

Statement::Run& Statement::Run::bind(int index, double value) {
  s_.db_.check(sqlite3_bind_double(s_.stmt_, index, value), s_.operation_);
  return *this;
}

Statement::Run& Statement::Run::bind(int index, std::int64_t value) {
  s_.db_.check(sqlite3_bind_int64(s_.stmt_, index, value), s_.operation_);
  return *this;
}

Statement::Run& Statement::Run::bind(int index, std::string_view value) {
  s_.db_.check(sqlite3_bind_text64(s_.stmt_, index, value.data(), value.size(), SQLITE_TRANSIENT, SQLITE_UTF8),
               s_.operation_);
  return *this;
}

Statement::Run& Statement::Run::bind(int index, std::optional<double> value) {
  if (value) return bind(index, *value);
  s_.db_.check(sqlite3_bind_null(s_.stmt_, index), s_.operation_);
  return *this;
}

Statement::Run& Statement::Run::bind(int index, std::optional<std::int64_t> value) {
  if (value) return bind(index, *value);
  s_.db_.check(sqlite3_bind_null(s_.stmt_, index), s_.operation_);
  return *this;
}

bool Statement::Run::step() {
  const int rc = sqlite3_step(s_.stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  s_.db_.fail(rc, s_.operation_);
}

void Statement::Run::execute() {
  while (step()) {
  }
}

double Statement::Run::column_double(int index) const { return sqlite3_column_double(s_.stmt_, index); }

std::int64_t Statement::Run::column_int(int index) const { return sqlite3_column_int64(s_.stmt_, index); }

std::string Statement::Run::column_text(int index) const {
  const unsigned char* text = sqlite3_column_text(s_.stmt_, index);
  return text ? std::string(reinterpret_cast<const char*>(text),
                            static_cast<std::size_t>(sqlite3_column_bytes(s_.stmt_, index)))
              : std::string();
}

bool Statement::Run::column_is_null(int index) const { return sqlite3_column_type(s_.stmt_, index) == SQLITE_NULL; }

Transaction::Transaction(Connection& db, std::string_view operation) : db_(db), operation_(operation) {
  db_.exec("BEGIN IMMEDIATE", "begin " + operation_);
}

Transaction::~Transaction() {
  if (open_) sqlite3_exec(db_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
}

void Transaction::commit() {
  db_.exec("COMMIT", "commit " + operation_);
  open_ = false;
}

}  // namespace ambid::diag::sqlite
