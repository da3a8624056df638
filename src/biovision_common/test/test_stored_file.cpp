#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>

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
  EXPECT_FALSE(std::ifstream(path + ".tmp." + std::to_string(::getpid())).good());
  std::remove(path.c_str());
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

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
