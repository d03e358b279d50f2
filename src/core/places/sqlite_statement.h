#pragma once
// SQLite helpers of the place database (place_database*.cpp only; not installed): a prepared
// statement that finalizes itself and throws naming the file, and a transaction that rolls back
// unless committed.
#include <sqlite3.h>

#include <stdexcept>
#include <string>

namespace adaptive_perception::places::sqlite_detail {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the stored blobs are little-endian");

// A prepared statement that finalizes itself.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql, const std::string& path) : db_(db), path_(path) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
      throw std::runtime_error(path + ": " + sqlite3_errmsg(db) + " (in: " + sql + ")");
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int i, const std::string& s) {
    check(sqlite3_bind_text(stmt_, i, s.c_str(), -1, SQLITE_TRANSIENT));
    return *this;
  }
  Statement& bind(int i, long long v) {
    check(sqlite3_bind_int64(stmt_, i, v));
    return *this;
  }
  Statement& bind(int i, double v) {
    check(sqlite3_bind_double(stmt_, i, v));
    return *this;
  }
  Statement& bindBlob(int i, const void* data, int bytes) {
    check(sqlite3_bind_blob(stmt_, i, data, bytes, SQLITE_TRANSIENT));
    return *this;
  }
  /// True while there is a row.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw std::runtime_error(path_ + ": " + sqlite3_errmsg(db_));
  }
  void reset() {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  long long integer(int col) const { return sqlite3_column_int64(stmt_, col); }
  std::string text(int col) const {
    const unsigned char* t = sqlite3_column_text(stmt_, col);
    return t ? reinterpret_cast<const char*>(t) : "";
  }
  const void* blob(int col) const { return sqlite3_column_blob(stmt_, col); }
  double real(int col) const { return sqlite3_column_double(stmt_, col); }
  bool isNull(int col) const { return sqlite3_column_type(stmt_, col) == SQLITE_NULL; }
  int bytes(int col) const { return sqlite3_column_bytes(stmt_, col); }

 private:
  void check(int rc) {
    if (rc != SQLITE_OK) throw std::runtime_error(path_ + ": " + sqlite3_errmsg(db_));
  }
  sqlite3* db_;
  std::string path_;
  sqlite3_stmt* stmt_ = nullptr;
};

// Rolls back unless committed. Inside a batch (PlaceDatabase::beginBatch: a transaction already
// open) it is a savepoint, so the change still succeeds or fails as a whole and the batch commits
// everything at once.
class Transaction {
 public:
  Transaction(sqlite3* db, const std::string& path)
      : db_(db), path_(path), nested_(sqlite3_get_autocommit(db) == 0) {
    run(nested_ ? "SAVEPOINT change" : "BEGIN IMMEDIATE");
  }
  ~Transaction() {
    if (done_) return;
    if (nested_)
      sqlite3_exec(db_, "ROLLBACK TO change; RELEASE change", nullptr, nullptr, nullptr);
    else
      sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void commit() {
    run(nested_ ? "RELEASE change" : "COMMIT");
    done_ = true;
  }

 private:
  void run(const char* sql) {
    char* err = nullptr;
    if (sqlite3_exec(db_, sql, nullptr, nullptr, &err) != SQLITE_OK) {
      const std::string msg = err ? err : "unknown error";
      sqlite3_free(err);
      throw std::runtime_error(path_ + ": " + msg);
    }
  }
  sqlite3* db_;
  std::string path_;
  bool nested_;
  bool done_ = false;
};

}  // namespace adaptive_perception::places::sqlite_detail
