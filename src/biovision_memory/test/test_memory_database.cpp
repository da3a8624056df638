#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <sqlite3.h>

#include "biovision_memory/memory_database.hpp"

using namespace biovision_memory;

namespace
{
class MemoryDatabaseTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    char tmpl[] = "/tmp/biovision_memory_db_XXXXXX";
    dir_ = mkdtemp(tmpl);
    path_ = dir_ + "/memory.db";
  }
  void TearDown() override { std::system(("rm -rf " + dir_).c_str()); }

  // An LTM with `n` cells and an object memory with two objects.
  static void fill(LongTermMemory& ltm, ObjectMemory& om, int n)
  {
    for (int i = 0; i < n; ++i)
      ltm.observe(0.1 * i + 0.05, -0.3 + 0.01 * (i % 7), 1.0 + i);
    om.observe("cup", {1.0, 2.0, 0.8}, 5.0);
    om.observe("cup", {1.0, 2.0, 0.8}, 6.0);
    om.observe("box \"A\"; DROP TABLE objects", {-1.0, 0.5, 0.1}, 7.0);
  }

  static void rawSql(const std::string& path, const std::string& sql)
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
    sqlite3_close(db);
  }

  std::string dir_, path_;
};

std::string errorOf(const std::string& path, const MemoryDatabase::Options& options)
{
  try
  {
    MemoryDatabase db(path, options);
  }
  catch (const DatabaseError& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_F(MemoryDatabaseTest, RoundTripKeepsEveryFieldAndDeletions)
{
  LongTermMemory ltm;
  ObjectMemory om;
  fill(ltm, om, 50);
  {
    MemoryDatabase db(path_, {});
    db.save(ltm.takeChanges(), om.takeChanges());
    // Remove some, change one.
    ltm.observe(0.05, -0.3, 100.0);  // cell 0 reinforced
    om.remove("cup");
    ltm.forget(1e9);  // every unfixed cell is gone
    db.save(ltm.takeChanges(), om.takeChanges());
  }
  LongTermMemory ltm2;
  ObjectMemory om2;
  fill(ltm2, om2, 50);
  ltm2.observe(0.05, -0.3, 100.0);
  om2.remove("cup");
  ltm2.forget(1e9);
  MemoryDatabase db(path_, {});
  const auto cells = db.loadCells();
  const auto objects = db.loadObjects();
  EXPECT_EQ(cells.size(), ltm2.cells().size());
  for (const auto& c : cells)
  {
    const auto it = ltm2.cells().find(LongTermMemory::key(c.ix, c.iy));
    ASSERT_NE(it, ltm2.cells().end());
    EXPECT_EQ(c.strength, it->second.strength);
    EXPECT_EQ(c.observations, it->second.observations);
    EXPECT_DOUBLE_EQ(c.first_seen, it->second.first_seen);
    EXPECT_DOUBLE_EQ(c.last_seen, it->second.last_seen);
    EXPECT_DOUBLE_EQ(c.last_change, it->second.last_change);
  }
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0].label, "box \"A\"; DROP TABLE objects");
  EXPECT_EQ(objects[0].position, Eigen::Vector3d(-1.0, 0.5, 0.1));
  EXPECT_EQ(objects[0].strength, 40);
  EXPECT_DOUBLE_EQ(objects[0].first_seen, 7.0);
}

TEST_F(MemoryDatabaseTest, RoundTripOfAFullMap)
{
  LongTermMemory ltm;
  ObjectMemory om;
  fill(ltm, om, 500);
  {
    MemoryDatabase db(path_, {});
    db.save(ltm.takeChanges(), om.takeChanges());
  }
  MemoryDatabase db(path_, {});
  EXPECT_EQ(db.loadCells().size(), ltm.cells().size());
  EXPECT_EQ(db.loadObjects().size(), 2u);
}

TEST_F(MemoryDatabaseTest, ClearForgetsEverythingStoredAndStaysUsable)
{
  LongTermMemory ltm;
  ObjectMemory om;
  fill(ltm, om, 50);
  {
    MemoryDatabase db(path_, {});
    db.save(ltm.takeChanges(), om.takeChanges());
  }
  {
    MemoryDatabase db(path_, {});
    ASSERT_EQ(db.loadObjects().size(), 2u);
    db.clear();
    EXPECT_TRUE(db.loadCells().empty());
    EXPECT_TRUE(db.loadObjects().empty());
    // What is learnt afterwards is saved and loads again.
    ObjectMemory later;
    later.observe("mug", {0.5, 0.5, 0.5}, 9.0);
    db.save({}, later.takeChanges());
  }
  MemoryDatabase db(path_, {});
  EXPECT_TRUE(db.loadCells().empty());
  ASSERT_EQ(db.loadObjects().size(), 1u);
  EXPECT_EQ(db.loadObjects().front().label, "mug");
}

TEST_F(MemoryDatabaseTest, ANewerSchemaIsRefusedUnlessToldToStartEmpty)
{
  {
    MemoryDatabase db(path_, {});
  }
  rawSql(path_, "PRAGMA user_version = 7");
  const std::string e = errorOf(path_, {});
  EXPECT_NE(e.find("schema version 7 is newer"), std::string::npos) << e;
  EXPECT_NE(e.find(path_), std::string::npos) << e;
  MemoryDatabase::Options start_empty;
  start_empty.start_empty_on_bad = true;
  MemoryDatabase db(path_, start_empty);
  EXPECT_FALSE(db.movedAside().empty());
  EXPECT_EQ(access(db.movedAside().c_str(), F_OK), 0);
  EXPECT_TRUE(db.loadCells().empty());
}

TEST_F(MemoryDatabaseTest, AnotherCellSizeIsRefused)
{
  {
    MemoryDatabase db(path_, {});
  }
  MemoryDatabase::Options other;
  other.cell_size = 0.2;
  EXPECT_NE(errorOf(path_, other).find("cell_size"), std::string::npos);
}

TEST_F(MemoryDatabaseTest, AMissingFolderIsMadeAndAnUnwritableOneNamedInTheError)
{
  const std::string nested = dir_ + "/run/today/memory.db";
  {
    MemoryDatabase db(nested, {});  // the folders did not exist
  }
  EXPECT_TRUE(std::ifstream(nested).good());
  EXPECT_NE(errorOf("/proc/no_such_folder/memory.db", {}).find("lock file"), std::string::npos);
}

TEST_F(MemoryDatabaseTest, ACorruptFileIsRefused)
{
  {
    LongTermMemory ltm;
    ObjectMemory om;
    fill(ltm, om, 2000);  // several pages
    MemoryDatabase db(path_, {});
    db.save(ltm.takeChanges(), om.takeChanges());
  }
  rawSql(path_, "PRAGMA wal_checkpoint(TRUNCATE)");
  {
    std::fstream f(path_, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(0, std::ios::end);
    const long size = f.tellg();
    ASSERT_GT(size, 4 * 4096);
    f.seekp(4096);  // every page after the header page up to the middle: the tables' b-trees
    const std::string garbage(size / 2 - 4096, '\x5a');
    f.write(garbage.data(), garbage.size());
  }
  const std::string e = errorOf(path_, {});
  EXPECT_NE(e.find("corrupt"), std::string::npos) << "error: [" << e << "]";
  // Not a database at all.
  std::ofstream(path_, std::ios::trunc) << std::string(8192, 'x');
  const std::string e2 = errorOf(path_, {});
  EXPECT_NE(e2.find(path_), std::string::npos) << e2;
  EXPECT_FALSE(e2.empty());
  MemoryDatabase::Options start_empty;
  start_empty.start_empty_on_bad = true;
  MemoryDatabase db(path_, start_empty);
  EXPECT_TRUE(db.loadObjects().empty());
}

TEST_F(MemoryDatabaseTest, ASecondOpenerIsRefusedInThisAndInAnotherProcess)
{
  MemoryDatabase db(path_, {});
  const std::string e = errorOf(path_, {});
  EXPECT_NE(e.find("in use by another process"), std::string::npos) << e;
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0)
  {
    try
    {
      MemoryDatabase other(path_, {});
      _exit(0);
    }
    catch (const DatabaseError&)
    {
      _exit(3);
    }
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3);
}

// A child writes one object per transaction and reports each commit through a pipe; SIGKILL mid-loop;
// the database reopens intact and holds every reported transaction.
TEST_F(MemoryDatabaseTest, KillNineDuringWritesLosesNothingCommitted)
{
  for (int round = 0; round < 3; ++round)
  {
    int fds[2];
    ASSERT_EQ(pipe(fds), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0)
    {
      close(fds[0]);
      try
      {
        MemoryDatabase db(path_, {});
        LongTermMemory ltm;
        ObjectMemory om;
        for (int i = 0;; ++i)
        {
          om.observe("o" + std::to_string(round) + "_" + std::to_string(i), {1.0 * i, 0.0, 0.0}, i);
          for (int k = 0; k < 20; ++k)
            ltm.observe(0.1 * k + 0.05, 0.1 * i + 0.05, i);
          db.save(ltm.takeChanges(), om.takeChanges());
          const int n = i;
          if (write(fds[1], &n, sizeof(n)) != sizeof(n))
            _exit(2);
        }
      }
      catch (...)
      {
        _exit(1);
      }
    }
    close(fds[1]);
    int last = -1, n = 0;
    while (last < 30 + 20 * round && read(fds[0], &n, sizeof(n)) == sizeof(n))
      last = n;
    kill(child, SIGKILL);
    while (read(fds[0], &n, sizeof(n)) == sizeof(n))
      last = n;  // commits reported before it died
    close(fds[0]);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the child ended on its own, status " << status;
    MemoryDatabase db(path_, {});  // integrity check passes, lock released
    const auto objects = db.loadObjects();
    int found = 0;
    for (const auto& o : objects)
      if (o.label.rfind("o" + std::to_string(round) + "_", 0) == 0)
      {
        const int i = std::stoi(o.label.substr(o.label.find('_') + 1));
        if (i <= last)
          ++found;
      }
    EXPECT_EQ(found, last + 1) << "round " << round;
    EXPECT_GE(static_cast<int>(db.loadCells().size()), 20 * (last + 1));
  }
}

TEST_F(MemoryDatabaseTest, AFullDiskFailsTheSaveKeepsTheChangesAndTheDatabase)
{
  MemoryDatabase::Options small;
  small.max_pages = 8;
  LongTermMemory ltm;
  ObjectMemory om;
  {
    MemoryDatabase db(path_, small);
    om.observe("first", {0, 0, 0}, 1.0);
    db.save(ltm.takeChanges(), om.takeChanges());
    for (int i = 0; i < 5000; ++i)
      ltm.observe(0.1 * i + 0.05, 0.05, 2.0);
    try
    {
      db.save(ltm.takeChanges(), om.takeChanges());
      FAIL() << "a 5000-cell save fit into 8 pages";
    }
    catch (const DatabaseError& e)
    {
      EXPECT_NE(std::string(e.what()).find("full"), std::string::npos) << e.what();
    }
    EXPECT_EQ(db.pending(), 5000u);
  }
  MemoryDatabase db(path_, {});
  EXPECT_EQ(db.loadObjects().size(), 1u);
  EXPECT_TRUE(db.loadCells().empty());
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

// Issue 23 item 4 for the database: a readable file with a value out of range is refused naming the row
// and the field, not loaded into the memory.
TEST_F(MemoryDatabaseTest, NonFiniteOrOutOfRangeValuesAreRefusedNamingTheField)
{
  struct Case
  {
    const char* sql;
    const char* expected;
  };
  const std::vector<Case> cases{
      {"UPDATE objects SET x = 1e400 WHERE label = 'cup'", "objects row 'cup': x = inf is not finite"},
      {"UPDATE objects SET z = -5e7 WHERE label = 'cup'", "objects row 'cup': z = -5e+07 is outside"},
      {"UPDATE objects SET strength = -3 WHERE label = 'cup'", "objects row 'cup': strength = -3"},
      {"UPDATE objects SET last_seen = -1e400 WHERE label = 'cup'", "objects row 'cup': last_seen = -inf"},
      {"UPDATE objects SET label = '' WHERE label = 'cup'", "objects row '': empty label"},
      {"UPDATE objects SET label = replace(hex(zeroblob(2500)), '0', 'x') WHERE label = 'cup'", "label of 5000 bytes"},
      {"UPDATE ltm_cells SET strength = 1000000 WHERE ix = 0", "strength = 1e+06 is outside"},
      {"UPDATE ltm_cells SET first_seen = 1e400 WHERE ix = 0", "first_seen = inf is not finite"},
  };
  for (const auto& c : cases)
  {
    std::filesystem::remove(path_);
    {
      LongTermMemory ltm;
      ObjectMemory om;
      fill(ltm, om, 3);
      MemoryDatabase db(path_, {});
      db.save(ltm.takeChanges(), om.takeChanges());
    }
    rawSql(path_, c.sql);
    const std::string e = errorOf(path_, {});
    EXPECT_NE(e.find(c.expected), std::string::npos) << c.sql << " -> [" << e << "]";
    EXPECT_NE(e.find(path_), std::string::npos) << e;
    if (std::string(c.sql).find("ltm_cells") != std::string::npos)
    {
      EXPECT_NE(e.find("ltm_cells row (0, "), std::string::npos) << e;
    }
  }
}

// Issue 23 item 1 for the database: a label the loader would refuse is refused when remembering it.
TEST_F(MemoryDatabaseTest, WhatIsRememberedLoadsAgain)
{
  ObjectMemory om;
  EXPECT_THROW(om.observe(std::string(5000, 'x'), {1.0, 2.0, 0.5}, 1.0), std::invalid_argument);
  EXPECT_THROW(om.observe("tab\there", {1.0, 2.0, 0.5}, 1.0), std::invalid_argument);
  om.observe(std::string(256, 'y'), {1.0, 2.0, 0.5}, 1.0);  // at the limit
  LongTermMemory ltm;
  {
    MemoryDatabase db(path_, {});
    db.save(ltm.takeChanges(), om.takeChanges());
  }
  MemoryDatabase db(path_, {});
  ASSERT_EQ(db.loadObjects().size(), 1u);
  EXPECT_EQ(db.loadObjects()[0].label, std::string(256, 'y'));
}

// Issue 23 item 2 for the database: refusals within the same second keep every copy (the old
// `<db>.bad-<unix time>` name was replaced by the second one), with the WAL beside it.
TEST_F(MemoryDatabaseTest, ARefusedDatabaseIsKeptWithoutOverwritingAnEarlierCopy)
{
  MemoryDatabase::Options start_empty;
  start_empty.start_empty_on_bad = true;
  std::vector<std::string> kept;
  for (int i = 0; i < 3; ++i)
  {
    std::ofstream(path_, std::ios::trunc) << std::string(8192, char('a' + i));  // not a database
    MemoryDatabase db(path_, start_empty);
    kept.push_back(db.movedAside());
    EXPECT_EQ(kept.back().rfind(path_ + ".refused-", 0), 0u) << kept.back();
    EXPECT_FALSE(db.refusal().empty());
  }
  for (int i = 0; i < 3; ++i)
  {
    std::ifstream in(kept[i]);
    std::string content;
    in >> content;
    EXPECT_EQ(content, std::string(8192, char('a' + i))) << kept[i];
  }
  EXPECT_NE(kept[0], kept[1]);
  EXPECT_NE(kept[1], kept[2]);
}
