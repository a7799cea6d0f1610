#pragma once
// Thin RAII wrappers over the SQLite C API for the trend store. Every failure becomes an
// ambid::Error "trend store <file>: <operation>: <sqlite message> (code N)".
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

struct sqlite3;
struct sqlite3_stmt;

namespace ambid::diag::sqlite {

class Connection {
 public:
  // Opens (read_only) or opens-or-creates the database file.
  Connection(const std::string& path, bool read_only);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  void set_busy_timeout(int milliseconds);
  void exec(std::string_view sql, std::string_view operation);
  // Rows changed by the last INSERT, UPDATE or DELETE.
  std::int64_t changes() const;
  // Runs a statement that returns one row with one text or integer column (a PRAGMA query).
  std::string query_text(std::string_view sql, std::string_view operation);
  std::int64_t query_int(std::string_view sql, std::string_view operation);

  [[noreturn]] void fail(int code, std::string_view operation) const;
  void check(int code, std::string_view operation) const;
  sqlite3* handle() const { return db_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

// A prepared statement, kept for the connection's life and reused. Use it through a Run,
// which resets it (and so ends its read of the database) however the run ends.
class Statement {
 public:
  Statement(Connection& db, std::string_view sql, std::string_view operation);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  class Run {
   public:
    ~Run();
    Run(const Run&) = delete;
    Run& operator=(const Run&) = delete;

    Run& bind(int index, double value);
    Run& bind(int index, std::int64_t value);
    Run& bind(int index, std::string_view value);
    Run& bind(int index, std::optional<double> value);
    Run& bind(int index, std::optional<std::int64_t> value);
    // True while a row is available; false when done.
    bool step();
    // Steps a statement that returns no rows.
    void execute();

    double column_double(int index) const;
    std::int64_t column_int(int index) const;
    std::string column_text(int index) const;
    bool column_is_null(int index) const;

   private:
    friend class Statement;
    explicit Run(Statement& statement) : s_(statement) {}
    Statement& s_;
  };

  Run run() { return Run(*this); }

 private:
  Connection& db_;
  std::string operation_;
  sqlite3_stmt* stmt_ = nullptr;
};

// BEGIN IMMEDIATE (takes the write lock at once, waiting up to the busy timeout) ... COMMIT;
// rolled back by the destructor unless committed.
class Transaction {
 public:
  Transaction(Connection& db, std::string_view operation);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  Connection& db_;
  std::string operation_;
  bool open_ = true;
};

}  // namespace ambid::diag::sqlite
