// Builds an object memory file from template images: a folder per object (every image in it is a view),
// or COIL-style files label__ANGLE.png (views at multiples of --template-step).

#include <sys/stat.h>

#include <algorithm>
#include <iostream>
#include <regex>

#include <opencv2/imgcodecs.hpp>
#include <ros/package.h>

#include "biovision_recognition/descriptor_model.hpp"
#include "biovision_recognition/object_recognizer.hpp"
#include "biovision_v1/input_image.hpp"
#include "biovision_common/tool_options.hpp"

using namespace biovision_recognition;
using biovision_common::listDirectory;

namespace
{
bool isDirectory(const std::string& path)
{
  struct stat s;
  return stat(path.c_str(), &s) == 0 && S_ISDIR(s.st_mode);
}
}  // namespace

int main(int argc, char** argv)
{
  std::string root, out, model = ros::package::getPath("biovision_recognition") + "/models/" + kDefaultModelFile;
  int step = 20;
  biovision_common::ToolOptions options(
      "build_object_memory",
      "Builds an object memory file from template images: a folder per object (every image in it is a view), or\n"
      "COIL-style files LABEL__ANGLE.png (views at multiples of --template-step).");
  CLI::App& app = options.app();
  app.add_option("--templates", root,
                 "a folder per object (label = folder name; every image is a view), or files LABEL__ANGLE.png")
      ->required()
      ->check(CLI::ExistingDirectory);
  app.add_option("--out", out, "the object memory, written atomically (load it with the node's ~memory_file)")
      ->required();
  app.add_option("--model", model, "descriptor model");
  app.add_option("--template-step", step, "COIL naming: views at multiples of this [deg]")
      ->check(biovision_common::kPositive);
  options.parse(argc, argv);
  try
  {
    auto descriptor = std::make_shared<const V1Descriptor>(DescriptorModel::load(model));
    ObjectRecognizer recognizer(descriptor, ObjectRecognizer::Parameters());
    ObjectMemory memory(descriptor->model().bits(), descriptor->model().id());
    const std::regex coil(R"((.+)__(\d+)\.(png|jpg|ppm))");
    auto add = [&](const std::string& path, const std::string& label) {
      const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
      if (image.empty())
      {
        std::cerr << "skipping " << path << ": not an image\n";
        return;
      }
      ObjectView view = recognizer.describe(biovision_v1::InputImage(image).gray(), cv::Rect(), label);
      const std::string problem = recognizer.learnProblem(view);  // the node's learn_object rule
      if (!problem.empty())
      {
        std::cerr << "skipping " << path << ": " << problem << "\n";
        return;
      }
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
    memory.save(out);
    std::cerr << "wrote " << out << ": " << memory.labels().size() << " objects, " << memory.views().size()
              << " views, " << memory.codeCount() << " codes (descriptor " << memory.descriptorId() << ")\n";
  }
  catch (const std::exception& e)
  {
    std::cerr << "build_object_memory: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
