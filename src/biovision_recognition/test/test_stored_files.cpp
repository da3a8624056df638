#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>

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
