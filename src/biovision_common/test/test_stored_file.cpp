#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "biovision_common/atomic_file.hpp"
#include "biovision_common/payload_writer.hpp"
#include "biovision_common/stored_file.hpp"

using namespace biovision_common;

namespace
{
std::string tempPath(const std::string& name)
{
  return testing::TempDir() + "/biovision_common_" + name;
}

std::vector<uint8_t> fileBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes)
{
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}
}  // namespace

TEST(StoredFile, Crc32MatchesTheStandardCheckValue)
{
  const std::string s = "123456789";
  EXPECT_EQ(StoredFile::crc32(reinterpret_cast<const uint8_t*>(s.data()), s.size()), 0xCBF43926u);
}

TEST(StoredFile, RoundTripAndEveryKindOfDamageIsRefused)
{
  const std::string path = tempPath("stored.bin");
  const std::vector<uint8_t> payload{1, 2, 3, 4, 5, 6, 7};
  StoredFile::write(path, "TEST", 3, payload);
  EXPECT_EQ(StoredFile::read(path, "TEST", 3), payload);
  EXPECT_THROW(StoredFile::read(path, "OTHER", 3), StoredFileError);  // foreign
  EXPECT_THROW(StoredFile::read(path, "TEST", 4), StoredFileError);   // version
  EXPECT_THROW(StoredFile::read(path + ".missing", "TEST", 3), StoredFileError);
  auto bytes = fileBytes(path);
  auto flipped = bytes;
  flipped[26] ^= 0x10;  // inside the payload
  writeBytes(path, flipped);
  EXPECT_THROW(StoredFile::read(path, "TEST", 3), StoredFileError);
  writeBytes(path, std::vector<uint8_t>(bytes.begin(), bytes.end() - 3));  // truncated
  EXPECT_THROW(StoredFile::read(path, "TEST", 3), StoredFileError);
  writeBytes(path, {});
  EXPECT_THROW(StoredFile::read(path, "TEST", 3), StoredFileError);
  std::remove(path.c_str());
}

TEST(StoredFile, WriteLeavesNoTemporaryBehind)
{
  const std::string path = tempPath("atomic.bin");
  StoredFile::write(path, "TEST", 1, {9});
  StoredFile::write(path, "TEST", 1, {8});
  EXPECT_EQ(StoredFile::read(path, "TEST", 1), std::vector<uint8_t>{8});
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(path).parent_path()))
    EXPECT_NE(entry.path().filename().string().rfind("atomic.bin.tmp.", 0), 0u) << entry.path();
  std::remove(path.c_str());
}

// Two threads of one process writing one path (the breaker's case: they shared "<path>.tmp.<pid>", so one
// renamed the other's half-written file into place): every read sees one whole file or the other.
TEST(StoredFile, ThreadsWritingOnePathNeverExposeAHalfFile)
{
  const std::string path = tempPath("threads.bin");
  StoredFile::write(path, "TEST", 1, std::vector<uint8_t>(4096, 1));
  std::atomic<bool> stop{false};
  std::atomic<int> write_failures{0};
  auto writer = [&](uint8_t value) {
    for (int i = 0; i < 150; ++i)
      try
      {
        StoredFile::write(path, "TEST", 1, std::vector<uint8_t>(4096, value));
      }
      catch (const std::exception&)
      {
        ++write_failures;
      }
  };
  int bad_reads = 0, reads = 0;
  std::thread reader([&] {
    while (!stop)
    {
      try
      {
        const auto v = StoredFile::read(path, "TEST", 1);
        bad_reads += v.size() != 4096 || (v.front() != 1 && v.front() != 2);
      }
      catch (const StoredFileError&)
      {
        ++bad_reads;
      }
      ++reads;
    }
  });
  std::thread a(writer, 1), b(writer, 2);
  a.join();
  b.join();
  stop = true;
  reader.join();
  EXPECT_EQ(write_failures, 0);
  EXPECT_EQ(bad_reads, 0) << "of " << reads << " reads";
  std::remove(path.c_str());
}

TEST(StoredFile, ADirectoryOrAFifoIsRefusedWithoutBlocking)
{
  const std::string dir = tempPath("a_directory");
  std::filesystem::create_directories(dir);
  EXPECT_THROW(StoredFile::read(dir, "TEST", 1), StoredFileError);
  const std::string fifo = tempPath("a_fifo");
  std::remove(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THROW(StoredFile::read(fifo, "TEST", 1), StoredFileError);  // opening it would wait for a writer
  std::remove(fifo.c_str());
  std::filesystem::remove_all(dir);
}

TEST(StoredFile, LoadRefusesAPayloadTheParserDoesNotConsume)
{
  const std::string path = tempPath("load.bin");
  PayloadWriter w;
  w.put<uint32_t>(7);
  w.putString("seven");
  StoredFile::write(path, "TEST", 1, w.bytes());
  const auto parsed = StoredFile::load<std::string>(path, "TEST", 1, "test file", [](PayloadReader& r) {
    EXPECT_EQ(r.get<uint32_t>(), 7u);
    return r.getString();
  });
  EXPECT_EQ(parsed, "seven");
  // A parser that stops early (trailing bytes) or reads past the end is refused, naming what was read.
  EXPECT_THROW(StoredFile::load<int>(path, "TEST", 1, "test file",
                                     [](PayloadReader& r) { return int(r.get<uint32_t>()); }),
               StoredFileError);
  EXPECT_THROW(StoredFile::load<int>(path, "TEST", 1, "test file",
                                     [](PayloadReader& r) {
                                       r.getArray<uint64_t>(1000);
                                       return 0;
                                     }),
               StoredFileError);
  std::remove(path.c_str());
}

TEST(AtomicFile, ReplacesTheFileAndThrowsNamingAnUnwritableFolder)
{
  const std::string path = tempPath("atomic.txt");
  writeFileAtomically(path, std::string("first"));
  writeFileAtomically(path, std::string("second"));
  const auto bytes = fileBytes(path);
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "second");
  try
  {
    writeFileAtomically("/nonexistent-folder/x.txt", std::string("x"));
    FAIL() << "no exception";
  }
  catch (const FileError& e)
  {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/x.txt"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

TEST(AtomicFile, ListDirectorySortsAndSkipsHiddenEntries)
{
  const std::string dir = tempPath("listing");
  std::remove((dir + "/b").c_str());
  ::mkdir(dir.c_str(), 0755);
  for (const char* name : {"b", "a", ".hidden"})
    writeFileAtomically(dir + "/" + name, std::string("x"));
  EXPECT_EQ(listDirectory(dir), (std::vector<std::string>{"a", "b"}));
  EXPECT_TRUE(listDirectory(dir + "/missing").empty());
}

// Issue 23 item 3: kill -9 during a save leaves `<file>.tmp.<pid>` behind; they must not pile up.
TEST(AtomicFile, RemovesTemporariesOfDeadProcessesOnly)
{
  const std::string dir = tempPath("stale");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/memory.bin";
  // A process that ran and is gone: its pid is free (reuse within this test is practically impossible).
  const pid_t child = ::fork();
  if (child == 0)
    ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);
  const std::string dead = path + ".tmp." + std::to_string(child);
  const std::string alive = path + ".tmp." + std::to_string(::getppid());
  const std::string own = path + ".tmp." + std::to_string(::getpid());
  const std::string foreign = path + ".tmp.notapid";
  const std::string other = dir + "/other.bin.tmp." + std::to_string(child);
  // Today's names carry a per-call number: <pid>.<n>.
  const std::string dead_numbered = dead + ".7", alive_numbered = alive + ".2", odd = dead + ".x";
  for (const auto& f : {dead, alive, own, foreign, other, dead_numbered, alive_numbered, odd})
    writeBytes(f, {1, 2, 3});
  const auto removed = removeStaleTemporaries(path);
  EXPECT_EQ(removed, (std::vector<std::string>{dead, dead_numbered}));
  EXPECT_FALSE(std::filesystem::exists(dead));
  for (const auto& f : {alive, own, foreign, other, alive_numbered, odd})
    EXPECT_TRUE(std::filesystem::exists(f)) << f;
  // A bare file name (the current folder) and a missing folder do not throw.
  EXPECT_TRUE(removeStaleTemporaries(dir + "/missing/memory.bin").empty());
  std::filesystem::remove_all(dir);
}

// Issue 23 item 2: a second refusal must not overwrite the copy kept from the first.
TEST(AtomicFile, KeepAsideNeverOverwritesAnEarlierCopy)
{
  const std::string dir = tempPath("aside");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/memory.bin";
  std::vector<std::string> kept;
  for (uint8_t i = 0; i < 3; ++i)  // three refusals within the same second
  {
    writeBytes(path, {i});
    kept.push_back(keepAside(path));
    EXPECT_FALSE(std::filesystem::exists(path));
  }
  for (uint8_t i = 0; i < 3; ++i)
  {
    EXPECT_EQ(kept[i].rfind(path + ".refused-", 0), 0u) << kept[i];
    EXPECT_EQ(fileBytes(kept[i]), std::vector<uint8_t>{i}) << kept[i];
  }
  EXPECT_NE(kept[0], kept[1]);
  EXPECT_NE(kept[1], kept[2]);
  writeBytes(path, {7});
  EXPECT_FALSE(moveWithoutOverwriting(path, kept[0]));
  EXPECT_EQ(fileBytes(kept[0]), std::vector<uint8_t>{0});
  EXPECT_THROW(keepAside(dir + "/missing.bin"), FileError);
  std::filesystem::remove_all(dir);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
