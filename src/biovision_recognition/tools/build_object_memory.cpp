// Builds an object memory file from template images: a folder per object (every image in it is a view),
// or COIL-style files label__ANGLE.png (views at multiples of --template-step).

#include <sys/stat.h>

#include <algorithm>
#include <iostream>
#include <regex>

#include <opencv2/imgcodecs.hpp>
#include <ros/package.h>

#include "biovision_recognition/object_recognizer.hpp"
#include "biovision_v1/input_image.hpp"
#include "biovision_common/tool_arguments.hpp"

using namespace biovision_recognition;
using biovision_common::listDirectory;
using biovision_common::ToolArguments;

namespace
{
const char* kUsage =
    "usage: build_object_memory --templates DIR --out FILE [--model FILE] [--template-step DEG]\n"
    "  --templates DIR      a folder per object (label = folder name; every image is a view), or\n"
    "                       files LABEL__ANGLE.png (COIL naming): views at multiples of --template-step (default 20)\n"
    "  --model FILE         descriptor model (default: the package's models/v1_ldahash_128.bin)\n"
    "  --out FILE           the object memory, written atomically (load it with the node's ~memory_file)\n";

bool isDirectory(const std::string& path)
{
  struct stat s;
  return stat(path.c_str(), &s) == 0 && S_ISDIR(s.st_mode);
}
}  // namespace

int main(int argc, char** argv)
{
  const ToolArguments args(argc, argv, kUsage, {"--templates", "--out", "--model", "--template-step"});
  if (!args.has("--templates") || !args.has("--out"))
  {
    std::cerr << kUsage;
    return 2;
  }
  try
  {
    const std::string model = args.get("--model", ros::package::getPath("biovision_recognition") + "/models/v1_ldahash_128.bin");
    auto descriptor = std::make_shared<const V1Descriptor>(DescriptorModel::load(model));
    ObjectRecognizer recognizer(descriptor, ObjectRecognizer::Parameters());
    ObjectMemory memory(descriptor->model().bits(), descriptor->model().id());
    const std::string root = args.get("--templates");
    const int step = static_cast<int>(args.number("--template-step", 20));
    const std::regex coil(R"((.+)__(\d+)\.(png|jpg|ppm))");
    auto add = [&](const std::string& path, const std::string& label) {
      const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
      if (image.empty())
      {
        std::cerr << "skipping " << path << ": not an image\n";
        return;
      }
      ObjectView view = recognizer.describe(biovision_v1::InputImage(image).gray(), cv::Rect(), label);
      std::cerr << label << ": " << path << " -> " << view.keypoints.size() << " keypoints\n";
      memory.addView(std::move(view));
    };
    for (const auto& name : listDirectory(root))
    {
      const std::string path = root + "/" + name;
      std::smatch m;
      if (isDirectory(path))
      {
        for (const auto& f : listDirectory(path))
          add(path + "/" + f, name);
      }
      else if (std::regex_match(name, m, coil) && std::stoi(m[2]) % step == 0)
        add(path, m[1]);
    }
    if (memory.views().empty())
      throw std::runtime_error("no template views found in " + root);
    memory.save(args.get("--out"));
    std::cerr << "wrote " << args.get("--out") << ": " << memory.labels().size() << " objects, " << memory.views().size()
              << " views, " << memory.codeCount() << " codes (descriptor " << memory.descriptorId() << ")\n";
  }
  catch (const std::exception& e)
  {
    std::cerr << "build_object_memory: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
