#pragma once

#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "biovision_memory/long_term_memory.hpp"
#include "biovision_memory/object_memory.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace biovision_memory
{
/// A database that cannot be used: in use by another process, corrupt, of a newer schema, written with
/// another cell size, or a failed write (disk full, I/O error). what() names the file and the reason.
class DatabaseError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// The long-term map and the object/landmark memory in one SQLite database (Debian's libsqlite3), as
/// rtabmap keeps its long-term memory:
///  - WAL journal, synchronous=FULL: every committed transaction survives a kill -9 or a power cut;
///  - schema version in `PRAGMA user_version` (kSchemaVersion); a newer one is refused;
///  - `PRAGMA integrity_check` on open; a corrupt file is refused; so is a row with a value out of range;
///  - one writer: an exclusive flock() on `<path>.lock` (released by the kernel when the process dies,
///    so a killed node never leaves a stale lock); a second process opening the same database is refused;
///  - changes are written incrementally (save()) in one transaction each.
/// Tables (inspect with `sqlite3 memory.db`): `ltm_cells(ix, iy, x, y, strength, observations,
/// first_seen, last_seen, last_change)`, `objects(label, x, y, z, strength, observations, first_seen,
/// last_seen, last_change)`, `meta(key, value)` (cell_size). Times are ROS time [s]; positions `map` [m].
class MemoryDatabase
{
public:
  static constexpr int kSchemaVersion = 1;
  /// Bounds of stored values, checked on open (a row outside them refuses the database, naming the row and
  /// the field): strengths are the reinforcement rules' [0, max_strength ≤ 100000], positions are in the
  /// map frame [m], times ROS time [s]; every value must be finite, every label follow
  /// biovision_common::ObjectLabel (as when it was learned).
  static constexpr double kMaxStrength = 100000;
  static constexpr double kMaxCoordinate = 1e6;  ///< [m]
  static constexpr double kMaxTime = 1e11;       ///< [s], about 3000 years

  struct Options
  {
    double cell_size = 0.1;  ///< the LTM's cell size [m]; a database written with another is refused
    /// Refused (corrupt, newer schema, other cell size, a value out of range): false → throw; true → move
    /// the file (and its -wal/-shm) aside to `<path>.refused-<UTC time>` — never overwriting an earlier
    /// kept copy — and start with an empty memory (movedAside() names it, refusal() says why). Never
    /// applies to "in use by another process".
    bool start_empty_on_bad = false;
    /// Upper bound of the file size in pages (PRAGMA max_page_count, 0 = SQLite's default), to keep the
    /// memory from filling a disk; a write beyond it fails like a full disk.
    long max_pages = 0;
  };

  /// Opens or creates `path`. Throws DatabaseError (see Options::start_empty_on_bad).
  MemoryDatabase(const std::string& path, const Options& options);
  ~MemoryDatabase();
  MemoryDatabase(const MemoryDatabase&) = delete;
  MemoryDatabase& operator=(const MemoryDatabase&) = delete;

  std::vector<LongTermMemory::Cell> loadCells() const;
  std::vector<ObjectMemory::Object> loadObjects() const;

  /// Writes the changes in one transaction. On failure (disk full, I/O error) throws DatabaseError and
  /// keeps them: the next save() writes them together with its own (later changes win), so nothing is
  /// lost while the process runs. The database keeps its last committed state.
  void save(const LongTermMemory::Changes& cells, const ObjectMemory::Changes& objects);
  /// Forgets everything stored (map cells and objects) in one transaction, and any pending changes: a
  /// robot that starts a new mission knowing nothing (the memory nodelet's ~start_empty). Throws
  /// DatabaseError when the transaction fails (the database then keeps its contents).
  void clear();
  /// Changes waiting for a successful save() (after a failed one).
  size_t pending() const { return pending_cells_.size() + pending_objects_.size(); }

  const std::string& path() const { return path_; }
  /// The file a bad database was moved to on open, or "".
  const std::string& movedAside() const { return moved_aside_; }
  /// Why it was moved aside, or "".
  const std::string& refusal() const { return refusal_; }

private:
  void open();
  void close();
  void check();  // throws DatabaseError on corruption, newer schema, other cell size
  void createSchema();
  void exec(const std::string& sql) const;
  /// BEGIN IMMEDIATE, body, COMMIT; ROLLBACK and rethrow when anything throws. The pending changes are
  /// dropped only after the commit.
  void writeTransaction(const std::function<void()>& body);
  std::string fail(const std::string& what) const;
  void checkValue(const std::string& row, const char* field, double value, double low, double high) const;
  /// The reinforcement fields every table keeps in this order from column `first`: strength, observations,
  /// first_seen, last_seen, last_change.
  void checkReinforcement(const std::string& row, sqlite3_stmt* statement, int first) const;

  std::string path_;
  Options options_;
  int lock_fd_ = -1;
  sqlite3* db_ = nullptr;
  std::string moved_aside_, refusal_;
  std::map<std::pair<int, int>, std::optional<LongTermMemory::Cell>> pending_cells_;
  std::map<std::string, std::optional<ObjectMemory::Object>> pending_objects_;
};
}  // namespace biovision_memory
