#include "biovision_memory/memory_database.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <sstream>

#include <sqlite3.h>

#include "biovision_common/atomic_file.hpp"
#include "biovision_common/object_label.hpp"

namespace biovision_memory
{
namespace
{
// A prepared statement, finalized on scope exit.
class Statement
{
public:
  Statement(sqlite3* db, const char* sql, const std::string& path)
  {
    if (sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr) != SQLITE_OK)
      throw DatabaseError(path + ": " + sqlite3_errmsg(db) + " (preparing: " + sql + ")");
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  sqlite3_stmt* get() const { return stmt_; }
  void reset() const
  {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }

private:
  sqlite3_stmt* stmt_ = nullptr;
};

bool fileExists(const std::string& path)
{
  return ::access(path.c_str(), F_OK) == 0;
}
}  // namespace

MemoryDatabase::MemoryDatabase(const std::string& path, const Options& options) : path_(path), options_(options)
{
  if (path.empty())
    throw DatabaseError("MemoryDatabase: empty path");
  if (!(options.cell_size > 0.0) || !std::isfinite(options.cell_size))
    throw DatabaseError(path + ": cell_size must be > 0");
  // A run's output folder may not exist yet (mission.launch puts the database there): make it.
  std::error_code ignored;
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty())
    std::filesystem::create_directories(parent, ignored);  // a failure shows as the lock file's error below
  // One writer: the lock file is held for the object's lifetime; the kernel drops it when we die.
  const std::string lock_path = path + ".lock";
  lock_fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0)
    throw DatabaseError(path + ": cannot create the lock file " + lock_path + ": " + std::strerror(errno));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0)
  {
    char buffer[32] = {0};
    const ssize_t n = ::pread(lock_fd_, buffer, sizeof(buffer) - 1, 0);
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw DatabaseError(path + ": in use by another process" +
                        (n > 0 ? std::string(" (pid ") + std::string(buffer, n) + ")" : std::string()) +
                        "; a memory database has one writer");
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(lock_fd_, 0) == 0)
  {
    [[maybe_unused]] const ssize_t w = ::pwrite(lock_fd_, pid.data(), pid.size(), 0);
  }
  try
  {
    try
    {
      open();
      check();
    }
    catch (const DatabaseError& e)
    {
      close();
      if (!options_.start_empty_on_bad)
        throw;
      refusal_ = e.what();
      try
      {
        // A timestamped name no later refusal overwrites; the journal files go with it.
        moved_aside_ = biovision_common::keepAside(path);
        for (const char* suffix : {"-wal", "-shm"})
          if (fileExists(path + suffix) &&
              !biovision_common::moveWithoutOverwriting(path + suffix, moved_aside_ + suffix))
            throw biovision_common::FileError(moved_aside_ + suffix + " exists");
      }
      catch (const biovision_common::FileError& move)
      {
        throw DatabaseError(std::string(e.what()) + "; moving it aside failed: " + move.what());
      }
      open();
      check();
    }
  }
  catch (...)
  {
    close();
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw;
  }
}

MemoryDatabase::~MemoryDatabase()
{
  close();
  if (lock_fd_ >= 0)
    ::close(lock_fd_);
}

void MemoryDatabase::checkReinforcement(const std::string& row, sqlite3_stmt* statement, int first) const
{
  checkValue(row, "strength", sqlite3_column_double(statement, first), 0, kMaxStrength);
  checkValue(row, "observations", sqlite3_column_double(statement, first + 1), 0, 4294967295.0);
  checkValue(row, "first_seen", sqlite3_column_double(statement, first + 2), -kMaxTime, kMaxTime);
  checkValue(row, "last_seen", sqlite3_column_double(statement, first + 3), -kMaxTime, kMaxTime);
  checkValue(row, "last_change", sqlite3_column_double(statement, first + 4), -kMaxTime, kMaxTime);
}

void MemoryDatabase::checkValue(const std::string& row, const char* field, double value, double low, double high) const
{
  if (!std::isfinite(value) || value < low || value > high)
  {
    std::ostringstream m;
    m << path_ << ": " << row << ": " << field << " = " << value << " is "
      << (std::isfinite(value) ? "outside [" : "not finite [") << low << ", " << high << "]";
    throw DatabaseError(m.str());
  }
}

std::string MemoryDatabase::fail(const std::string& what) const
{
  return path_ + ": " + what + (db_ ? std::string(": ") + sqlite3_errmsg(db_) : std::string());
}

void MemoryDatabase::exec(const std::string& sql) const
{
  char* message = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK)
  {
    const std::string m = message ? message : sqlite3_errmsg(db_);
    sqlite3_free(message);
    throw DatabaseError(path_ + ": " + m + " (" + sql + ")");
  }
}

void MemoryDatabase::open()
{
  if (sqlite3_open_v2(path_.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX,
                      nullptr) != SQLITE_OK)
  {
    const std::string m = fail("cannot open");
    close();
    throw DatabaseError(m);
  }
  sqlite3_extended_result_codes(db_, 1);
  sqlite3_busy_timeout(db_, 2000);
}

void MemoryDatabase::close()
{
  if (db_)
    sqlite3_close_v2(db_);
  db_ = nullptr;
}

void MemoryDatabase::check()
{
  int version = -1;
  {
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db_, "PRAGMA user_version", -1, &s, nullptr) != SQLITE_OK || sqlite3_step(s) != SQLITE_ROW)
    {
      sqlite3_finalize(s);
      throw DatabaseError(fail("not a readable SQLite database (corrupt?)"));
    }
    version = sqlite3_column_int(s, 0);
    sqlite3_finalize(s);
  }
  if (version > kSchemaVersion)
    throw DatabaseError(path_ + ": schema version " + std::to_string(version) + " is newer than this program's " +
                        std::to_string(kSchemaVersion) + "; refusing to touch it");
  {
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db_, "PRAGMA integrity_check", -1, &s, nullptr) != SQLITE_OK)
      throw DatabaseError(fail("integrity check could not run (corrupt?)"));
    std::string result;
    int rc;
    while ((rc = sqlite3_step(s)) == SQLITE_ROW)
    {
      const unsigned char* text = sqlite3_column_text(s, 0);
      if (!result.empty())
        result += "; ";
      result += text ? reinterpret_cast<const char*>(text) : "";
      if (result.size() > 300)
        break;
    }
    sqlite3_finalize(s);
    if (rc != SQLITE_ROW && rc != SQLITE_DONE)
      throw DatabaseError(fail("corrupt (integrity check failed)"));
    if (result != "ok")
      throw DatabaseError(path_ + ": corrupt, PRAGMA integrity_check says: " + result);
  }
  exec("PRAGMA journal_mode=WAL");
  exec("PRAGMA synchronous=FULL");
  if (options_.max_pages > 0)
    exec("PRAGMA max_page_count=" + std::to_string(options_.max_pages));
  if (version == 0)
    createSchema();
  Statement s(db_, "SELECT value FROM meta WHERE key = 'cell_size'", path_);
  if (sqlite3_step(s.get()) == SQLITE_ROW)
  {
    const double stored = sqlite3_column_double(s.get(), 0);
    if (std::abs(stored - options_.cell_size) > 1e-9)
    {
      std::ostringstream m;
      m << path_ << ": written with cell_size " << stored << " m, asked for " << options_.cell_size
        << " m; refusing to mix them";
      throw DatabaseError(m.str());
    }
  }
  // Every stored value is checked here, so a bad row refuses the file (and start_empty_on_bad moves it
  // aside) instead of reaching the memory.
  loadCells();
  loadObjects();
}

void MemoryDatabase::createSchema()
{
  std::ostringstream cell;
  cell.precision(17);
  cell << options_.cell_size;
  exec("BEGIN IMMEDIATE");
  try
  {
    exec(
        "CREATE TABLE IF NOT EXISTS ltm_cells (ix INTEGER NOT NULL, iy INTEGER NOT NULL, x REAL NOT NULL, "
        "y REAL NOT NULL, strength INTEGER NOT NULL, observations INTEGER NOT NULL, first_seen REAL NOT NULL, "
        "last_seen REAL NOT NULL, last_change REAL NOT NULL, PRIMARY KEY (ix, iy)) WITHOUT ROWID");
    exec(
        "CREATE TABLE IF NOT EXISTS objects (label TEXT PRIMARY KEY NOT NULL, x REAL NOT NULL, y REAL NOT NULL, "
        "z REAL NOT NULL, strength INTEGER NOT NULL, observations INTEGER NOT NULL, first_seen REAL NOT NULL, "
        "last_seen REAL NOT NULL, last_change REAL NOT NULL)");
    exec("CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY NOT NULL, value TEXT NOT NULL)");
    exec("INSERT OR REPLACE INTO meta (key, value) VALUES ('cell_size', '" + cell.str() + "')");
    exec("PRAGMA user_version = " + std::to_string(kSchemaVersion));
    exec("COMMIT");
  }
  catch (...)
  {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

std::vector<LongTermMemory::Cell> MemoryDatabase::loadCells() const
{
  std::vector<LongTermMemory::Cell> cells;
  Statement s(db_,
              "SELECT ix, iy, strength, observations, first_seen, last_seen, last_change FROM ltm_cells "
              "ORDER BY ix, iy",
              path_);
  int rc;
  while ((rc = sqlite3_step(s.get())) == SQLITE_ROW)
  {
    LongTermMemory::Cell c;
    c.ix = sqlite3_column_int(s.get(), 0);
    c.iy = sqlite3_column_int(s.get(), 1);
    c.strength = sqlite3_column_int(s.get(), 2);
    c.observations = static_cast<std::uint32_t>(sqlite3_column_int64(s.get(), 3));
    c.first_seen = sqlite3_column_double(s.get(), 4);
    c.last_seen = sqlite3_column_double(s.get(), 5);
    c.last_change = sqlite3_column_double(s.get(), 6);
    const std::string row = "ltm_cells row (" + std::to_string(c.ix) + ", " + std::to_string(c.iy) + ")";
    checkReinforcement(row, s.get(), 2);
    cells.push_back(c);
  }
  if (rc != SQLITE_DONE)
    throw DatabaseError(fail("reading ltm_cells failed"));
  return cells;
}

std::vector<ObjectMemory::Object> MemoryDatabase::loadObjects() const
{
  std::vector<ObjectMemory::Object> objects;
  Statement s(db_,
              "SELECT label, x, y, z, strength, observations, first_seen, last_seen, last_change FROM objects "
              "ORDER BY label",
              path_);
  int rc;
  while ((rc = sqlite3_step(s.get())) == SQLITE_ROW)
  {
    ObjectMemory::Object o;
    const unsigned char* label = sqlite3_column_text(s.get(), 0);
    o.label = label ? reinterpret_cast<const char*>(label) : "";
    o.position = {sqlite3_column_double(s.get(), 1), sqlite3_column_double(s.get(), 2),
                  sqlite3_column_double(s.get(), 3)};
    o.strength = sqlite3_column_int(s.get(), 4);
    o.observations = static_cast<std::uint32_t>(sqlite3_column_int64(s.get(), 5));
    o.first_seen = sqlite3_column_double(s.get(), 6);
    o.last_seen = sqlite3_column_double(s.get(), 7);
    o.last_change = sqlite3_column_double(s.get(), 8);
    const std::string problem = biovision_common::ObjectLabel::problem(o.label);
    if (!problem.empty())
      throw DatabaseError(path_ + ": objects row '" + o.label.substr(0, 40) + "': " + problem);
    const std::string row = "objects row '" + o.label + "'";
    checkValue(row, "x", o.position.x(), -kMaxCoordinate, kMaxCoordinate);
    checkValue(row, "y", o.position.y(), -kMaxCoordinate, kMaxCoordinate);
    checkValue(row, "z", o.position.z(), -kMaxCoordinate, kMaxCoordinate);
    checkReinforcement(row, s.get(), 4);
    objects.push_back(o);
  }
  if (rc != SQLITE_DONE)
    throw DatabaseError(fail("reading objects failed"));
  return objects;
}

void MemoryDatabase::save(const LongTermMemory::Changes& cells, const ObjectMemory::Changes& objects)
{
  for (const auto& r : cells.removed)
    pending_cells_[r] = std::nullopt;
  for (const auto& c : cells.upserted)
    pending_cells_[{c.ix, c.iy}] = c;
  for (const auto& label : objects.removed)
    pending_objects_[label] = std::nullopt;
  for (const auto& o : objects.upserted)
    pending_objects_[o.label] = o;
  if (pending_cells_.empty() && pending_objects_.empty())
    return;
  auto step = [&](const Statement& s, const char* what) {
    const int rc = sqlite3_step(s.get());
    s.reset();
    if (rc != SQLITE_DONE)
      throw DatabaseError(fail(std::string("writing ") + what + " failed"));
  };
  writeTransaction([&] {
    Statement put_cell(db_,
                       "INSERT OR REPLACE INTO ltm_cells (ix, iy, x, y, strength, observations, first_seen, "
                       "last_seen, last_change) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
                       path_);
    Statement delete_cell(db_, "DELETE FROM ltm_cells WHERE ix = ? AND iy = ?", path_);
    Statement put_object(db_,
                         "INSERT OR REPLACE INTO objects (label, x, y, z, strength, observations, first_seen, "
                         "last_seen, last_change) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
                         path_);
    Statement delete_object(db_, "DELETE FROM objects WHERE label = ?", path_);
    for (const auto& [key, cell] : pending_cells_)
    {
      if (!cell)
      {
        sqlite3_bind_int(delete_cell.get(), 1, key.first);
        sqlite3_bind_int(delete_cell.get(), 2, key.second);
        step(delete_cell, "ltm_cells");
        continue;
      }
      sqlite3_stmt* s = put_cell.get();
      sqlite3_bind_int(s, 1, cell->ix);
      sqlite3_bind_int(s, 2, cell->iy);
      sqlite3_bind_double(s, 3, (cell->ix + 0.5) * options_.cell_size);
      sqlite3_bind_double(s, 4, (cell->iy + 0.5) * options_.cell_size);
      sqlite3_bind_int(s, 5, cell->strength);
      sqlite3_bind_int64(s, 6, cell->observations);
      sqlite3_bind_double(s, 7, cell->first_seen);
      sqlite3_bind_double(s, 8, cell->last_seen);
      sqlite3_bind_double(s, 9, cell->last_change);
      step(put_cell, "ltm_cells");
    }
    for (const auto& [label, object] : pending_objects_)
    {
      if (!object)
      {
        sqlite3_bind_text(delete_object.get(), 1, label.c_str(), -1, SQLITE_TRANSIENT);
        step(delete_object, "objects");
        continue;
      }
      sqlite3_stmt* s = put_object.get();
      sqlite3_bind_text(s, 1, label.c_str(), -1, SQLITE_TRANSIENT);
      sqlite3_bind_double(s, 2, object->position.x());
      sqlite3_bind_double(s, 3, object->position.y());
      sqlite3_bind_double(s, 4, object->position.z());
      sqlite3_bind_int(s, 5, object->strength);
      sqlite3_bind_int64(s, 6, object->observations);
      sqlite3_bind_double(s, 7, object->first_seen);
      sqlite3_bind_double(s, 8, object->last_seen);
      sqlite3_bind_double(s, 9, object->last_change);
      step(put_object, "objects");
    }
  });
}

void MemoryDatabase::clear()
{
  writeTransaction([this] {
    exec("DELETE FROM ltm_cells");
    exec("DELETE FROM objects");
  });
}

void MemoryDatabase::writeTransaction(const std::function<void()>& body)
{
  exec("BEGIN IMMEDIATE");
  try
  {
    body();
    exec("COMMIT");
  }
  catch (...)
  {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  pending_cells_.clear();
  pending_objects_.clear();
}
}  // namespace biovision_memory
