#pragma once
// Thin RAII wrapper over the SQLite C API: a connection and prepared
// statements whose failures carry SQLite's own message.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

struct sqlite3;
struct sqlite3_stmt;

namespace hs::scene {

class SqliteDb {
 public:
  SqliteDb() = default;
  ~SqliteDb();
  SqliteDb(const SqliteDb&) = delete;
  SqliteDb& operator=(const SqliteDb&) = delete;

  bool open(const std::string& path, bool readOnly, bool create, std::string& error);
  void close();
  bool exec(const std::string& sql, std::string& error);
  std::string lastError() const;
  sqlite3* handle() const { return db_; }

 private:
  sqlite3* db_ = nullptr;
};

class SqliteStmt {
 public:
  SqliteStmt(SqliteDb& db, const std::string& sql);
  ~SqliteStmt();
  SqliteStmt(const SqliteStmt&) = delete;
  SqliteStmt& operator=(const SqliteStmt&) = delete;

  bool ok() const { return stmt_ != nullptr; }
  void bind(int index, std::string_view text);
  void bind(int index, int64_t value);
  void bindBlob(int index, std::span<const uint8_t> bytes);
  // SQLITE_ROW -> true; SQLITE_DONE -> false with error empty; else false with error set.
  bool step(std::string& error);
  void reset();
  std::string text(int column) const;
  int64_t integer(int column) const;
  std::span<const uint8_t> blob(int column) const;

 private:
  SqliteDb& db_;
  sqlite3_stmt* stmt_ = nullptr;
  std::string prepareError_;  // why it did not prepare ("no such table: blobs")
};

}  // namespace hs::scene
