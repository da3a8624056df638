// PicturePage: base64 by RFC 4648's test vectors; report.html embeds the pictures it can read and names
// the ones it cannot.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "biovision_common/picture_page.hpp"

using biovision_common::PicturePage;

TEST(PicturePage, Base64OfTheRfcVectors)
{
  EXPECT_EQ(PicturePage::base64({}), "");
  EXPECT_EQ(PicturePage::base64({'f'}), "Zg==");
  EXPECT_EQ(PicturePage::base64({'f', 'o'}), "Zm8=");
  EXPECT_EQ(PicturePage::base64({'f', 'o', 'o'}), "Zm9v");
  EXPECT_EQ(PicturePage::base64({'f', 'o', 'o', 'b', 'a', 'r'}), "Zm9vYmFy");
  EXPECT_EQ(PicturePage::base64({0xff, 0xfe}), "//4=");
}

TEST(PicturePage, EmbedsReadablePicturesAndNamesMissingOnes)
{
  const std::string dir = std::filesystem::temp_directory_path() / ("picture_page_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir + "/a.png", std::ios::binary);
    f << "foo";
  }
  EXPECT_EQ(PicturePage::write(dir, "seeds 1-2 <report>", "{\"reached\": 1}", {"a.png", "gone.png"}), 1);
  std::ifstream in(dir + "/report.html");
  std::stringstream text;
  text << in.rdbuf();
  const std::string page = text.str();
  EXPECT_NE(page.find("<h1>seeds 1-2 &lt;report&gt;</h1>"), std::string::npos);
  EXPECT_NE(page.find("{&quot;reached&quot;: 1}"), std::string::npos);
  EXPECT_NE(page.find("alt=\"a.png\" src=\"data:image/png;base64,Zm9v\""), std::string::npos);
  EXPECT_NE(page.find("missing picture: gone.png"), std::string::npos);
  EXPECT_EQ(page.find("alt=\"gone.png\""), std::string::npos);
  std::filesystem::remove_all(dir);
}
