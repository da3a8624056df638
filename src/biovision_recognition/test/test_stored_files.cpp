#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <limits>
#include <fstream>
#include <random>

#include "biovision_common/payload_writer.hpp"
#include "biovision_common/stored_file.hpp"

#include "biovision_recognition/descriptor_model.hpp"
#include "biovision_recognition/object_memory.hpp"

using biovision_common::StoredFileError;

using namespace biovision_recognition;

namespace
{
std::string tempPath(const std::string& name)
{
  return testing::TempDir() + "/biovision_recognition_" + name;
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

DescriptorModel smallModel()
{
  DescriptorModel m;
  m.layout.scales = {4, 5};                  // few features: gridSide 3 and 1 -> 16 * (9 + 1)
  m.layout.shape.window_wavelengths = 1.25;  // not the default: the round trip must carry the shape fields
  m.layout.shape.max_anisotropy = 3.5;
  std::mt19937 rng(2);
  std::normal_distribution<float> g;
  m.projection.resize(64, m.layout.featureCount());
  for (Eigen::Index i = 0; i < m.projection.size(); ++i)
    m.projection.data()[i] = g(rng);
  m.thresholds = Eigen::VectorXf::Constant(64, 0.1f);
  m.provenance = "test";
  return m;
}

// Writes views as a BVOBJMEM v1 file by hand, bypassing addView(): a file another (older, buggy or
// tampered) writer produced, with a valid checksum.
void writeMemoryFile(const std::string& path, const std::vector<ObjectView>& views)
{
  biovision_common::PayloadWriter w;
  w.put<int32_t>(128);
  w.putString("model-a");
  w.put<uint64_t>(views.size());
  for (const auto& v : views)
  {
    w.putString(v.label);
    w.put<int32_t>(v.size.width);
    w.put<int32_t>(v.size.height);
    w.putArray(v.keypoints.data(), v.keypoints.size());
    w.putArray(v.codes.data(), v.codes.size() * v.codes.words());
  }
  biovision_common::StoredFile::write(path, "BVOBJMEM", 1, w.bytes());
}

std::string refusal(const std::string& path)
{
  try
  {
    ObjectMemory::load(path, "model-a");
  }
  catch (const StoredFileError& e)
  {
    return e.what();
  }
  return "(loaded)";
}

ObjectView view(const std::string& label, int n, uint64_t seed)
{
  ObjectView v;
  v.label = label;
  v.size = {64, 48};
  v.codes = BinaryCodeSet(128, n);
  std::mt19937_64 rng(seed);
  for (int i = 0; i < n; ++i)
  {
    v.keypoints.push_back({float(i), float(2 * i), 5.66f, 1.f, 0.f});
    v.codes.code(i)[0] = rng();
    v.codes.code(i)[1] = rng();
  }
  return v;
}
}  // namespace

TEST(DescriptorModel, RoundTripKeepsHalfPrecisionAndIdentity)
{
  const DescriptorModel m = smallModel();
  const std::string path = tempPath("model.bin");
  m.save(path);
  const DescriptorModel r = DescriptorModel::load(path);
  EXPECT_TRUE(r.layout == m.layout);
  EXPECT_EQ(r.provenance, "test");
  ASSERT_EQ(r.projection.rows(), m.projection.rows());
  EXPECT_LT((r.projection - m.projection).cwiseAbs().maxCoeff(), 2e-3f * m.projection.cwiseAbs().maxCoeff());
  EXPECT_EQ(r.thresholds, m.thresholds);
  EXPECT_EQ(DescriptorModel::load(path).id(), r.id());
  std::remove(path.c_str());
}

TEST(DescriptorModel, CorruptOrInconsistentModelIsRefused)
{
  const std::string path = tempPath("model_bad.bin");
  smallModel().save(path);
  auto bytes = fileBytes(path);
  bytes[bytes.size() / 2] ^= 0xFF;
  writeBytes(path, bytes);
  EXPECT_THROW(DescriptorModel::load(path), StoredFileError);
  // A well-formed file whose projection does not fit its layout: refused by validation.
  DescriptorModel m = smallModel();
  m.layout.scales = {4};
  EXPECT_THROW(m.save(path), std::invalid_argument);
  std::remove(path.c_str());
}

TEST(ObjectMemory, RoundTripRemoveAndDuplicateLabels)
{
  ObjectMemory memory(128, "model-a");
  memory.addView(view("cup", 10, 1));
  memory.addView(view("cup", 5, 2));  // a second view of the same label
  memory.addView(view("book", 7, 3));
  EXPECT_EQ(memory.labels(), (std::vector<std::string>{"book", "cup"}));
  EXPECT_EQ(memory.viewCount("cup"), 2u);
  EXPECT_EQ(memory.keypointCount("cup"), 15u);
  EXPECT_EQ(memory.codeCount(), 22u);
  const std::string path = tempPath("memory.bin");
  memory.save(path);
  const ObjectMemory loaded = ObjectMemory::load(path, "model-a");
  ASSERT_EQ(loaded.views().size(), 3u);
  EXPECT_EQ(loaded.views()[2].label, "book");
  EXPECT_EQ(loaded.views()[1].codes.code(4)[1], memory.views()[1].codes.code(4)[1]);
  EXPECT_EQ(loaded.views()[0].keypoints[3].y, 6.f);
  EXPECT_EQ(loaded.viewOf(12), 1u);
  EXPECT_EQ(loaded.keypointOf(12), 2u);
  ObjectMemory edited = loaded;
  EXPECT_EQ(edited.remove("cup"), 2u);
  EXPECT_EQ(edited.remove("cup"), 0u);
  EXPECT_EQ(edited.codeCount(), 7u);
  EXPECT_THROW(edited.addView(view("", 3, 4)), std::invalid_argument);
  ObjectView wrong = view("x", 3, 5);
  wrong.keypoints.pop_back();
  EXPECT_THROW(edited.addView(wrong), std::invalid_argument);
  std::remove(path.c_str());
}

TEST(ObjectMemory, CorruptTruncatedOrForeignMemoryIsRefused)
{
  ObjectMemory memory(128, "model-a");
  memory.addView(view("cup", 10, 1));
  const std::string path = tempPath("memory_bad.bin");
  memory.save(path);
  EXPECT_THROW(ObjectMemory::load(path, "model-b"), StoredFileError);  // built with another descriptor
  const auto bytes = fileBytes(path);
  writeBytes(path, std::vector<uint8_t>(bytes.begin(), bytes.begin() + bytes.size() / 2));
  EXPECT_THROW(ObjectMemory::load(path, "model-a"), StoredFileError);
  smallModel().save(path);  // a descriptor model is not an object memory
  EXPECT_THROW(ObjectMemory::load(path, "model-a"), StoredFileError);
  std::remove(path.c_str());
}

// Issue 23 item 1: a 5,000-character label was accepted and saved, and the next start refused the whole
// file. One schema on both sides: what addView accepts round-trips, what the loader would refuse is refused
// when learning.
TEST(ObjectMemory, WhatLearningAcceptsLoadingAcceptsAndLimitsAreEnforcedWhenLearning)
{
  ObjectMemory memory(128, "model-a");
  const std::string longest(ObjectMemory::kMaxLabelBytes, 'x');
  for (size_t i = 0; i < ObjectMemory::kMaxViewsPerObject; ++i)
    memory.addView(view(longest, 10, i));
  memory.addView(view("cup", 10, 99));
  const std::string path = tempPath("memory_limits.bin");
  memory.save(path);
  const ObjectMemory loaded = ObjectMemory::load(path, "model-a");
  EXPECT_EQ(loaded.viewCount(longest), ObjectMemory::kMaxViewsPerObject);
  EXPECT_EQ(loaded.viewCount("cup"), 1u);

  const size_t before = memory.views().size();
  try
  {
    memory.addView(view(std::string(5000, 'y'), 10, 1));
    FAIL() << "a 5000-byte label was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("5000 bytes"), std::string::npos) << e.what();
  }
  EXPECT_THROW(memory.addView(view(longest, 10, 1000)), std::invalid_argument);  // views per object
  EXPECT_THROW(memory.addView(view("line\nbreak", 10, 1)), std::invalid_argument);
  EXPECT_EQ(memory.views().size(), before);  // unchanged by refusals
  memory.save(path);
  EXPECT_EQ(ObjectMemory::load(path, "model-a").views().size(), before);

  // A file another writer made with a label over the limit: refused naming the field, not "inconsistent".
  writeMemoryFile(path, {view(std::string(5000, 'z'), 3, 1)});
  EXPECT_NE(refusal(path).find("label of 5000 bytes"), std::string::npos) << refusal(path);
  std::remove(path.c_str());
}

// Issue 23 item 4: a valid checksum but a NaN keypoint coordinate loaded silently and gave labels.
TEST(ObjectMemory, NonFiniteOrOutOfRangeValuesAreRefusedNamingTheField)
{
  const std::string path = tempPath("memory_values.bin");
  struct Case
  {
    const char* field;
    std::function<void(ObjectView&)> damage;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const std::vector<Case> cases{
      {"keypoint 2 x", [&](ObjectView& v) { v.keypoints[2].x = nan; }},
      {"keypoint 2 y", [&](ObjectView& v) { v.keypoints[2].y = inf; }},
      {"keypoint 2 x", [&](ObjectView& v) { v.keypoints[2].x = 1e9f; }},
      {"keypoint 2 y", [&](ObjectView& v) { v.keypoints[2].y = -3.f; }},
      {"keypoint 2 wavelength", [&](ObjectView& v) { v.keypoints[2].wavelength = 0.f; }},
      {"keypoint 2 strength", [&](ObjectView& v) { v.keypoints[2].strength = nan; }},
      {"keypoint 2 orientation", [&](ObjectView& v) { v.keypoints[2].orientation = -inf; }},
      {"size", [&](ObjectView& v) { v.size.width = 0; }},
      {"size", [&](ObjectView& v) { v.size.height = 1 << 20; }},
      {"empty label", [&](ObjectView& v) { v.label.clear(); }},
  };
  for (const auto& c : cases)
  {
    ObjectView bad = view("cup", 5, 1);
    c.damage(bad);
    writeMemoryFile(path, {view("book", 5, 2), bad});
    const std::string why = refusal(path);
    EXPECT_NE(why.find("view 1"), std::string::npos) << c.field << ": " << why;
    EXPECT_NE(why.find(c.field), std::string::npos) << c.field << ": " << why;
    // The same view is refused when learning, naming the same field.
    ObjectMemory memory(128, "model-a");
    try
    {
      memory.addView(bad);
      ADD_FAILURE() << c.field << " accepted by addView";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(c.field), std::string::npos) << e.what();
    }
  }
  writeMemoryFile(path, {view("book", 5, 2), view("cup", 5, 1)});  // the undamaged file loads
  EXPECT_EQ(ObjectMemory::load(path, "model-a").views().size(), 2u);
  std::remove(path.c_str());
}

// Issue 23 item 5: every kind of damage to a descriptor model names the file and the problem.
TEST(DescriptorModel, EveryDamageIsRefusedNamingTheFileAndTheProblem)
{
  const std::string path = tempPath("model_damage.bin");
  smallModel().save(path);
  const auto good = fileBytes(path);
  struct Case
  {
    const char* problem;
    std::vector<uint8_t> bytes;
  };
  std::vector<Case> cases;
  auto magic = good;
  magic[0] = 'X';
  cases.push_back({"magic", magic});
  auto version = good;
  version[8] = 99;
  cases.push_back({"version", version});
  cases.push_back({"truncated", std::vector<uint8_t>(good.begin(), good.end() - 100)});
  cases.push_back({"too short", std::vector<uint8_t>(good.begin(), good.begin() + 10)});
  cases.push_back({"too short", {}});
  auto flipped = good;
  flipped[good.size() / 2] ^= 0x01;
  cases.push_back({"checksum", flipped});
  for (const auto& c : cases)
  {
    writeBytes(path, c.bytes);
    try
    {
      DescriptorModel::load(path);
      ADD_FAILURE() << c.problem << ": loaded";
    }
    catch (const StoredFileError& e)
    {
      const std::string why = e.what();
      EXPECT_NE(why.find(path), std::string::npos) << why;
      EXPECT_NE(why.find(c.problem), std::string::npos) << c.problem << ": " << why;
    }
  }
  std::remove(path.c_str());
  try
  {
    DescriptorModel::load(path);
    ADD_FAILURE() << "a missing model loaded";
  }
  catch (const StoredFileError& e)
  {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}
