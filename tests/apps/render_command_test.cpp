// `ibfvs render` run as a user runs it: real process, exit status, stderr.
// Sections: help and outputs (PNG, videos, interruption, frames against the
// image) | flows, colour and data (elements, landscapes, scalars, the globe,
// unsteady fields, relief, topology) | options that fail cleanly | styles and
// locking | bad input (NaN vectors, malformed meshes, impossible options).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "command_runner.h"
#include "helpers.h"
#include "ibfvs/core/image/image.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"

namespace ibfvs {
namespace {

using RenderCommand = test::CommandTest;
using test::Result;

const char* kTri = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";

TEST_F(RenderCommand, HelpDocumentsEveryOptionWithDefaults) {
  const Result r = run("render --help");
  EXPECT_EQ(r.status, 0);
  for (const char* opt :
       {"--mesh",        "--field", "--tangent",     "--size",       "--frames",  "--out",
        "--texture-out", "--alpha", "--beta",        "--scale",      "--profile", "--vg",
        "--seed",        "--step",  "--dt",          "--background", "--camera",  "--ortho",
        "--fov",         "--orbit", "--advect-view", "--subdivide",  "--inject"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  EXPECT_NE(r.out.find("512x512"), std::string::npos);
  EXPECT_NE(r.out.find("0.5,0.5,0.5"), std::string::npos);
}

TEST_F(RenderCommand, RendersPngTextureAndSequence) {
  const std::string mesh = file("sq.off", kTri);
  const Result r =
      run("render --mesh sq.off --field uniform:1,0,0 --size 64x48 --frames 5 "
          "--out last.png --texture-out tex.png");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("wrote last.png"), std::string::npos) << r.out;
  const ImageU8 img = read_png(dir_ / "last.png");
  EXPECT_EQ(img.width, 64);
  EXPECT_EQ(img.height, 48);
  EXPECT_TRUE(std::filesystem::exists(dir_ / "tex.png"));
  const Result seq = run("render --mesh sq.off --size 32x32 --frames 3 --out f%03d.png -q");
  ASSERT_EQ(seq.status, 0) << seq.err;
  for (const char* f : {"f000.png", "f001.png", "f002.png"})
    EXPECT_TRUE(std::filesystem::exists(dir_ / f)) << f;
  EXPECT_TRUE(seq.out.empty());
}

TEST_F(RenderCommand, RendersVideo) {
  file("sq.off", kTri);
  const Result r = run("render --mesh sq.off --size 64x64 --frames 10 --out clip.mp4 -q");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string bytes = test::read_file(dir_ / "clip.mp4");
  ASSERT_GT(bytes.size(), 100u);
  EXPECT_EQ(bytes.substr(4, 4), "ftyp");
}

TEST_F(RenderCommand, VideoContainers) {
  // x264 in MP4, MKV and MOV, VP9 in WebM (in-process), GIF through the
  // ffmpeg program; each decodes back to its frames, and nothing but our
  // own lines reaches the terminal.
  for (const char* name : {"c.mp4", "c.mkv", "c.mov", "c.webm", "c.gif"}) {
    const Result r =
        run(std::string("render --mesh torus --size 48x32 --frames 5 -q --out ") + name);
    ASSERT_EQ(r.status, 0) << name << "\n" << r.err;
    EXPECT_TRUE(r.err.empty()) << name << "\n" << r.err;
    const std::string count =
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=nb_read_frames,width -of csv=p=0 '" +
        (dir_ / name).string() + "' > '" + (dir_ / "probe.txt").string() + "'";
    ASSERT_EQ(std::system(count.c_str()), 0) << count;
    EXPECT_EQ(test::read_file(dir_ / "probe.txt"), "48,5\n") << name;
  }
  // Every frame is in the file whatever the count: x264 leaves packet
  // durations unset, and MP4/MOV edit lists then ended at the last frame's
  // start, which players dropped (250 and 394 frames decoded as 249 and 393).
  for (const char* name : {"n.mp4", "n.mov"}) {
    for (const int n : {250, 394}) {
      const Result r = run("render --mesh torus --size 16x16 --frames " + std::to_string(n) +
                           " -q --out " + name);
      ASSERT_EQ(r.status, 0) << name << "\n" << r.err;
      const std::string count =
          "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
          "stream=nb_read_frames -of csv=p=0 '" +
          (dir_ / name).string() + "' > '" + (dir_ / "probe.txt").string() + "'";
      ASSERT_EQ(std::system(count.c_str()), 0) << count;
      EXPECT_EQ(test::read_file(dir_ / "probe.txt"), std::to_string(n) + "\n") << name;
    }
  }
  // A file the encoder cannot open: one clear line naming it, exit 1.
  std::filesystem::create_directory(dir_ / "taken.mp4");
  expect_error("render --mesh torus --size 48x32 --frames 2 --out taken.mp4",
               "--out: taken.mp4 is a folder");
}

// Outputs are whole or absent: Ctrl-C during a video finishes a shorter,
// valid file and says so (status 130); nothing is left under a temporary name.
TEST_F(RenderCommand, InterruptedVideoIsShorterAndWhole) {
  for (const char* name : {"i.mp4", "i.gif"}) {
    // SIGINT once the video has been opened (its temporary file exists) and
    // a second has passed, as a Ctrl-C would come.
    const std::string script =
        std::string("cd '") + dir_.path().string() + "' && ( '" + IBFVS_EXE +
        "' render --mesh torus --size 64x48 --frames 1000000 -q --out " + name +
        " 2>err.txt & p=$!; for k in $(seq 600); do ls .i.* >/dev/null 2>&1 && break; sleep 0.1; "
        "done; sleep 1; kill -INT $p; wait $p; echo $? > status.txt )";
    ASSERT_EQ(std::system(script.c_str()), 0);
    EXPECT_EQ(test::read_file(dir_ / "status.txt"), "130\n") << name;
    const std::string err = test::read_file(dir_ / "err.txt");
    EXPECT_NE(err.find("ibfvs: interrupted by Ctrl-C after "), std::string::npos) << err;
    EXPECT_NE(err.find(std::string("of 1000000 frames: wrote ") + name + ", a shorter video of"),
              std::string::npos)
        << err;
    const std::string count =
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=nb_read_frames -of csv=p=0 '" +
        (dir_ / name).string() + "' > '" + (dir_ / "probe.txt").string() + "'";
    ASSERT_EQ(std::system(count.c_str()), 0) << count;
    const int frames = std::stoi(test::read_file(dir_ / "probe.txt"));
    EXPECT_GT(frames, 0) << name;
    EXPECT_NE(err.find("a shorter video of " + std::to_string(frames) + " frames"),
              std::string::npos)
        << name << ": decoded " << frames << "\n"
        << err;
    for (const auto& entry : std::filesystem::directory_iterator(dir_.path()))
      EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos)
          << entry.path();
  }
}

// An output that is an input of the same run is refused before anything is
// written.
TEST_F(RenderCommand, OutputThatIsAnInputIsRefused) {
  ASSERT_EQ(run("render --mesh torus --size 32x32 --frames 1 -q --out tex.png").status, 0);
  const std::string before = test::read_file(dir_ / "tex.png");
  expect_error(
      "render --mesh torus --size 32x32 --frames 1 --surface-image tex.png --out ./tex.png",
      "--out: ./tex.png is an input of this render; writing it would destroy tex.png");
  expect_error(
      "render --mesh torus --size 32x32 --frames 1 --surface-image tex.png --out a.png "
      "--texture-out tex.png",
      "--texture-out: tex.png is an input of this render");
  EXPECT_EQ(test::read_file(dir_ / "tex.png"), before);
}

// The pip package's way (no FFmpeg libraries in its wheel): every container
// through the ffmpeg program that IBFVS_FFMPEG names, with the in-process
// encoder's codecs; an odd size padded to even as there, the frames in
// order and upright; a program that is not there one error line.
TEST_F(RenderCommand, VideoThroughTheFfmpegProgramAsThePipPackageWritesIt) {
  const std::string ffmpeg = "IBFVS_FFMPEG=/usr/bin/ffmpeg";
  for (const char* name : {"p.mp4", "p.mkv", "p.mov", "p.webm", "p.avi"}) {
    const Result r =
        run(std::string("render --mesh torus --size 47x32 --frames 5 -q --out ") + name, ffmpeg);
    ASSERT_EQ(r.status, 0) << name << "\n" << r.err;
    EXPECT_TRUE(r.err.empty()) << name << "\n" << r.err;
    const std::string count =
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=nb_read_frames,width,codec_name -of csv=p=0 '" +
        (dir_ / name).string() + "' > '" + (dir_ / "probe.txt").string() + "'";
    ASSERT_EQ(std::system(count.c_str()), 0) << count;
    const std::string codec = std::string(name) == "p.webm" ? "vp9" : "h264";
    EXPECT_EQ(test::read_file(dir_ / "probe.txt"), codec + ",48,5\n") << name;
  }
  const std::string common =
      "render --mesh torus --frames 12 --color-by y --color-map viridis --background "
      "0.8,0.2,0.1 --beta 0 -q --size 191x127 ";
  ASSERT_EQ(run(common + "--out still.png").status, 0);
  ASSERT_EQ(run(common + "--out piped.mp4", ffmpeg).status, 0);
  const std::string decode = "ffmpeg -v error -y -i '" + (dir_ / "piped.mp4").string() +
                             "' -vf select='eq(n\\,11)' -frames:v 1 '" +
                             (dir_ / "piped-last.png").string() + "'";
  ASSERT_EQ(std::system(decode.c_str()), 0) << decode;
  const ImageU8 want = read_png(dir_ / "still.png");
  const ImageU8 got = read_png(dir_ / "piped-last.png");
  ASSERT_EQ(got.width, 192);
  ASSERT_EQ(got.height, 128);
  double same = 0.0;
  for (int y = 0; y < want.height; ++y)
    for (int x = 0; x < want.width; ++x)
      for (int c = 0; c < 3; ++c) same += std::abs(got.at(x, y + 1, c) - want.at(x, y, c));
  // As the in-process encoder's (VideoFramesMatchTheRenderedImage): about 7.7.
  EXPECT_LT(same / (3.0 * want.width * want.height), 10.0);
  const Result missing =
      run("render --mesh torus --size 16x16 --frames 2 --out none.mp4", "IBFVS_FFMPEG=/no/ffmpeg");
  EXPECT_EQ(missing.status, 1) << missing.err;
  EXPECT_NE(missing.err.find("IBFVS_FFMPEG names no program"), std::string::npos) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "none.mp4"));
}

// The frames encoded are the frames rendered: the last one decoded from the
// MP4 matches the PNG of the same render (colours, orientation, plane order),
// for an even size and an odd one (padded by a column and a row).
TEST_F(RenderCommand, VideoFramesMatchTheRenderedImage) {
  const std::string common =
      "render --mesh torus --frames 12 --color-by y --color-map viridis --background "
      "0.8,0.2,0.1 --beta 0 -q ";
  for (const char* size : {"192x128", "191x127"}) {
    const std::string name = std::string("clip") + size;
    ASSERT_EQ(run(common + "--size " + size + " --out " + name + ".png").status, 0);
    const Result v = run(common + "--size " + size + " --out " + name + ".mp4");
    ASSERT_EQ(v.status, 0) << v.err;
    const std::string decode = "ffmpeg -v error -y -i '" + (dir_ / (name + ".mp4")).string() +
                               "' -vf select='eq(n\\,11)' -frames:v 1 '" +
                               (dir_ / (name + "-last.png")).string() + "'";
    ASSERT_EQ(std::system(decode.c_str()), 0) << decode;
    const ImageU8 want = read_png(dir_ / (name + ".png"));
    const ImageU8 got = read_png(dir_ / (name + "-last.png"));
    // An odd size is padded to even by one column and row.
    ASSERT_EQ(got.width, want.width + want.width % 2);
    ASSERT_EQ(got.height, want.height + want.height % 2);
    double same = 0.0, flipped = 0.0;
    for (int y = 0; y < want.height; ++y)
      for (int x = 0; x < want.width; ++x)
        for (int c = 0; c < 3; ++c) {
          // Rows bottom-up: a padded row is the top one, so the rows line up.
          same += std::abs(got.at(x, y + got.height - want.height, c) - want.at(x, y, c));
          flipped += std::abs(got.at(x, want.height - 1 - y, c) - want.at(x, y, c));
        }
    const double n = 3.0 * want.width * want.height;
    std::printf("%s: mean difference %.2f / 255 (upside down: %.2f)\n", size, same / n,
                flipped / n);
    // Lossy (crf 18, half-resolution chroma on a red background): measured
    // 7.4 and 7.7 for the two sizes; upside down 13.0 and 14.0.
    EXPECT_LT(same / n, 10.0) << size;
    EXPECT_LT(1.5 * same, flipped) << size;
  }
  // Our RGBA -> I420 conversion against ffmpeg's own, losslessly.
  const ImageU8 still = read_png(dir_ / "clip192x128.png");
  ImageU8 rgba(still.width, still.height, 4);
  for (std::size_t i = 0; i < rgba.pixels.size() / 4; ++i)
    for (int c = 0; c < 4; ++c)
      rgba.pixels[4 * i + c] = c < still.channels ? still.pixels[i * still.channels + c] : 255;
  std::vector<std::uint8_t> ours;
  to_yuv420(rgba, ours);
  const std::string convert = "ffmpeg -v error -y -i '" + (dir_ / "clip192x128.png").string() +
                              "' -f rawvideo -pix_fmt yuv420p '" + (dir_ / "ff.yuv").string() + "'";
  ASSERT_EQ(std::system(convert.c_str()), 0) << convert;
  const std::string theirs = test::read_file(dir_ / "ff.yuv");
  ASSERT_EQ(theirs.size(), ours.size());
  const std::size_t luma = 192 * 128;
  double luma_error = 0.0, chroma_error = 0.0;
  for (std::size_t i = 0; i < ours.size(); ++i) {
    const double d = std::abs(int(ours[i]) - int(static_cast<unsigned char>(theirs[i])));
    (i < luma ? luma_error : chroma_error) += d;
  }
  luma_error /= luma;
  chroma_error /= static_cast<double>(ours.size() - luma);
  std::printf("I420 against ffmpeg's conversion: mean |Y| %.3f, |U,V| %.3f\n", luma_error,
              chroma_error);
  EXPECT_LT(luma_error, 0.1);    // measured 0.004
  EXPECT_LT(chroma_error, 0.5);  // measured 0.135
}

TEST_F(RenderCommand, DemoFallsBackToAProceduralSurface) {
  const Result r = run("render --size 64x64 --frames 3 --out demo.png",
                       "IBFVS_DATA_DIR='" + (dir_ / "no-data").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("procedural torus"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("wrote demo.png"), std::string::npos) << r.out;
}

TEST_F(RenderCommand, FlowElementsAndLandscapes) {
  file("sq.off", kTri);
  const Result e =
      run("render --mesh sq.off --size 32x32 --frames 2 --out e.png "
          "--element 0.5,0.5,-1,0.5,0.5,1,1,0,0 --element 0,0,-1,0,0,1,0,-0.5,0");
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_NE(e.out.find("field elements:0,0,0 with 2 elements"), std::string::npos) << e.out;
  const Result l = run("render --mesh landscape:2:6:32 --size 32x32 --frames 2 --out l.png");
  ASSERT_EQ(l.status, 0) << l.err;
  EXPECT_NE(l.out.find("field gradient:down:0,1,0"), std::string::npos) << l.out;
  EXPECT_NE(l.out.find("2048 triangles"), std::string::npos) << l.out;
  const Result p =
      run("render --mesh landscape --field principal:max:rot90 --size 32x32 "
          "--frames 2 --out p.png -q");
  EXPECT_EQ(p.status, 0) << p.err;
  const std::string m = "render --mesh sq.off --frames 1 --out x.png ";
  expect_error(m + "--element 0,0,0,0,0,0,1,0,0", "--element: the flow element has zero length");
  expect_error(m + "--element 1,2,3", "--element: expected AX,AY,AZ,BX,BY,BZ");
  expect_error(m + "--element 0,0,0,0,1,0,1,0,0 --field rotate:0,1,0",
               "--element: needs field elements");
  expect_error(m + "--field principal:sideways", "--field");
  expect_error(m + "--field gradient:down:0,0,0", "--field");
  expect_error("render --mesh landscape:x --out x.png", "--mesh: landscape:x");
  expect_error("render --mesh landscape:1:3 --out x.png", "--mesh: landscape:1:3");
  expect_error("render --mesh landscape:1:8:9999 --out x.png", "4096");
  file("grid.txt", "# control heights\n0 0 0 0 0\n0 .1 .2 .1 0\n0 .2 .5 .2 0\n0 0 0 0 0\n");
  const Result g = run("render --mesh landscape:grid.txt:16 --size 32x32 --frames 2 --out g.png");
  EXPECT_EQ(g.status, 0) << g.err;
  EXPECT_NE(g.out.find("512 triangles"), std::string::npos) << g.out;
  file("ragged.txt", "0 0 0 0\n0 0 0\n0 0 0 0\n0 0 0 0\n");
  expect_error("render --mesh landscape:ragged.txt --out x.png", "ragged.txt: every row");
  file("small.txt", "0 0 0\n0 0 0\n0 0 0\n");
  expect_error("render --mesh landscape:small.txt --out x.png",
               "small.txt: height field: the control grid must be at least 4 x 4");
  file("word.txt", "0 0 0 0\n0 x 0 0\n");
  expect_error("render --mesh landscape:word.txt --out x.png", "word.txt: line 2: 'x'");
}

TEST_F(RenderCommand, ColourAndBetaByScalars) {
  file("sq.off", kTri);
  const Result r =
      run("render --mesh sq.off --size 32x32 --frames 2 --out c.png -q "
          "--field uniform:1,0,0 --color-by x --color-map coolwarm --beta-by speed "
          "--beta-range 0,2");
  EXPECT_EQ(r.status, 0) << r.err;
  const std::string m = "render --mesh sq.off --field uniform:1,0,0 --frames 1 --out x.png ";
  expect_error(m + "--color-by pressure", "--color-by: sq.off: no per-vertex scalar 'pressure'");
  expect_error(m + "--color-by x --color-map jet", "--color-map");
  expect_error(m + "--color-by x --color-range 1", "--color-range");
  expect_error(m + "--color-by x --color-range 2,1", "--color-range");
  expect_error(m + "--beta-by y --beta-range 0,nan", "--beta-range");
}

TEST_F(RenderCommand, WindOnTheGlobe) {
  expect_error("render --mesh globe:2 --field wind:missing.cdf --out x.png",
               "missing.cdf: no such file");
  expect_error("render --mesh globe:9 --out x.png", "--mesh: globe:9");
  expect_error("render --mesh globe:2 --scalar relief --out x.png",
               "--scalar: expected NAME=FILE:VAR");
  expect_error("render --mesh globe:2 --time -1 --out x.png", "--time");
  const std::string earth = std::string(IBFVS_TEST_DATA_DIR) + "/earth/";
  if (!std::filesystem::exists(earth + "monthly_navy_winds.cdf"))
    GTEST_SKIP() << "fetched data missing: " << earth;
  const std::string winds = earth + "monthly_navy_winds.cdf";
  expect_error("render --mesh globe:2 --field wind:" + winds + ":UWND:NOPE --out x.png",
               "no variable 'NOPE'");
  expect_error("render --mesh globe:2 --field wind:" + winds + " --time 132 --out x.png",
               "time index 132 is out of range for 'UWND' (132 time steps");
  expect_error("render --mesh globe:2 --scalar r=" + earth + "etopo20.cdf:RELIEF --out x.png",
               "no variable 'RELIEF'");
  const Result r =
      run("render --mesh globe:3 --field wind:" + winds + " --time 6 --scalar r=" + earth +
          "etopo20.cdf:ROSE --color-by r --beta-by speed --size 64x64 "
          "--frames 3 --out g.png");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("UWND:VWND at time index 6"), std::string::npos) << r.out;
}

TEST_F(RenderCommand, UnsteadyFields) {
  TriMesh sq = make_square(1.0f, 4);
  sq.vectors.assign(sq.vertex_count(), glm::vec3(1, 0, 0));
  write_ply(sq, dir_ / "f0.ply", true);
  sq.vectors.assign(sq.vertex_count(), glm::vec3(0, 1, 0));
  write_ply(sq, dir_ / "f1.ply", true);
  const Result r =
      run("render --mesh f0.ply --field-step f0.ply --field-step f1.ply "
          "--frames-per-step 3 --frames 8 --size 32x32 --out u.png -q");
  EXPECT_EQ(r.status, 0) << r.err;
  TriMesh small = make_square(1.0f, 2);
  small.vectors.assign(small.vertex_count(), glm::vec3(1, 0, 0));
  write_ply(small, dir_ / "small.ply", true);
  expect_error(
      "render --mesh f0.ply --field-step f0.ply --field-step small.ply --frames 8 "
      "--frames-per-step 2 --out x.png",
      "--field-step: small.ply: 9 vertices, the mesh has 25");
  expect_error("render --mesh f0.ply --field-step f0.ply --subdivide 1 --out x.png",
               "--field-step: cannot be combined with subdivide");
  expect_error("render --mesh f0.ply --time 3:1 --out x.png",
               "--time: the range 3:1 runs backwards");
  expect_error("render --mesh f0.ply --time 0:2 --out x.png", "--time: a range A:B needs a series");
  expect_error("render --mesh f0.ply --time x --out x.png", "--time");
  expect_error("render --mesh f0.ply --frames-per-step 0 --out x.png", "--frames-per-step");
  const std::string coads = std::string(IBFVS_TEST_DATA_DIR) + "/earth/coads_climatology.cdf";
  if (!std::filesystem::exists(coads)) GTEST_SKIP() << "fetched data missing: " << coads;
  const Result year = run("render --mesh globe:3 --field wind:" + coads +
                          ":UWND:VWND --time 0:11 --frames-per-step 2 --frames 25 --size 32x32 "
                          "--out y.png -q");
  EXPECT_EQ(year.status, 0) << year.err;
  expect_error("render --mesh globe:3 --field wind:" + coads +
                   ":UWND:VWND --time 0:12 --frames 2 --out x.png",
               "time index 12 is out of range");
}

TEST_F(RenderCommand, ReliefAndDisplacement) {
  file("sq.off", kTri);
  const Result d =
      run("render --mesh sq.off --field uniform:1,0,0 --displace x:0.2 --size 32x32 "
          "--frames 2 --out d.png -q");
  EXPECT_EQ(d.status, 0) << d.err;
  const std::string m = "render --mesh sq.off --field uniform:1,0,0 --frames 1 --out x.png ";
  expect_error(m + "--displace x", "--displace: expected NAME:FACTOR");
  expect_error(m + "--surface-image none.png", "none.png");
  file("bad.png", "not a png");
  expect_error(m + "--surface-image bad.png", "bad.png: cannot read as PNG");
  expect_error(m + "--displace x:big", "--displace: expected NAME:FACTOR");
  expect_error(m + "--displace depth:1", "--displace: sq.off: no per-vertex scalar 'depth'");
  expect_error("render --mesh relief:none.cdf:ROSE:0,10,0,10 --out x.png",
               "none.cdf: no such file");
  expect_error("render --mesh relief:f.cdf:ROSE:0,10,0 --out x.png", "expected 4 numbers");
  expect_error("render --mesh relief:f.cdf:ROSE:10,0,0,10 --out x.png", "the box needs");
  const std::string etopo = std::string(IBFVS_TEST_DATA_DIR) + "/earth/etopo60.cdf";
  if (!std::filesystem::exists(etopo)) GTEST_SKIP() << "fetched data missing: " << etopo;
  const Result r = run("render --mesh relief:" + etopo +
                       ":ROSE:-25,60,-40,45::64 --color-by ROSE "
                       "--size 48x48 --frames 2 --out r.png");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("field gradient:down"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("8192 triangles"), std::string::npos) << r.out;
}

// Figure 7 on terrain data as it usually comes, height along +Z: the style
// must look down the mesh's own height axis, send the colours downhill along
// it and lock only once they have reached the basin borders. (It used to look
// down +Y, edge-on, with the flow along -Y, and lock after 40 frames.)
TEST_F(RenderCommand, TopologyOnATerrainWithHeightAlongZ) {
  // Two round hills, summits at x = -0.5 and x = +0.5: every point's basin is
  // the hill on its side of x = 0.
  const int n = 61;
  std::string off =
      "OFF\n" + std::to_string(n * n) + " " + std::to_string(2 * (n - 1) * (n - 1)) + " 0\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float x = -1.0f + 2.0f * i / (n - 1), y = -1.0f + 2.0f * j / (n - 1);
      const float z = 0.3f * std::exp(-((x + 0.5f) * (x + 0.5f) + y * y) / 0.08f) +
                      0.3f * std::exp(-((x - 0.5f) * (x - 0.5f) + y * y) / 0.08f);
      off += std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i;
      off += "3 " + std::to_string(a) + " " + std::to_string(a + 1) + " " +
             std::to_string(a + n + 1) + "\n3 " + std::to_string(a) + " " +
             std::to_string(a + n + 1) + " " + std::to_string(a + n) + "\n";
    }
  file("hills.off", off);
  // The style's own run, seen from above at the end (beta 1: F is F_t, the
  // basin colours without shading).
  const Result r =
      run("render hills.off --style topology --size 160x160 --beta 1 "
          "--lock-camera 0,90,0 --out t.png");
  ASSERT_EQ(r.status, 0) << r.err;
  const ImageU8 img = read_png(dir_ / "t.png");
  // Pixels well inside each basin: |x| from about 0.2 to 0.8, |y| < 0.35.
  const auto purity = [&](int x0, int x1, std::array<int, 3>& mode) {
    std::map<std::array<int, 3>, int> counts;
    std::vector<std::array<int, 3>> colours;
    for (int y = 80 - 18; y <= 80 + 18; ++y)
      for (int x = x0; x <= x1; ++x) {
        const std::size_t at = (static_cast<std::size_t>(y) * img.width + x) * img.channels;
        const std::array<int, 3> c{img.pixels[at], img.pixels[at + 1], img.pixels[at + 2]};
        colours.push_back(c);
        ++counts[c];
      }
    mode = std::max_element(counts.begin(), counts.end(), [](const auto& a, const auto& b) {
             return a.second < b.second;
           })->first;
    std::size_t same = 0;
    for (const auto& c : colours)
      // Repeated bilinear resampling leaves faint rings (a few levels); other
      // cells' random colours lie much further apart.
      same += std::abs(c[0] - mode[0]) + std::abs(c[1] - mode[1]) + std::abs(c[2] - mode[2]) <= 30;
    return static_cast<double>(same) / static_cast<double>(colours.size());
  };
  std::array<int, 3> left{}, right{};
  const double pl = purity(80 - 43, 80 - 10, left), pr = purity(80 + 10, 80 + 43, right);
  std::printf("topology on a +Z terrain: basin purity %.3f (left), %.3f (right)\n", pl, pr);
  EXPECT_GT(pl, 0.97);
  EXPECT_GT(pr, 0.97);
  EXPECT_NE(left, right) << "both basins took one colour";
  for (const auto& mode : {left, right})
    EXPECT_GT(std::abs(mode[0] - 128) + std::abs(mode[1] - 128) + std::abs(mode[2] - 128), 12)
        << "the background, not the terrain (seen edge-on?)";
  EXPECT_NE(r.out.find("gradient:down:0,0,1:normalize"), std::string::npos) << r.out;
}

// The options and arguments this library work added fail as cleanly as the
// old ones: one line naming the flag, exit 1.
TEST_F(RenderCommand, NewOptionsFailCleanly) {
  file("sq.off", kTri);
  const std::string m = "render sq.off --frames 2 --size 32x32 --out x.png ";
  expect_error(m + "--up 0,0,0", "--up: the axis must not be zero");
  expect_error(m + "--up sideways", "--up: 'sideways' is not a finite number");
  expect_error(m + "--lock-at soon", "--lock-at: 'soon' must be a whole number");
  expect_error(m + "--frames 0", "--frames: 0 (automatic) needs lock_at auto");
  expect_error("render missing.off --out x.png", "missing.off");
  expect_error("render missing.toml", "missing.toml: no such scene file");
  expect_error("keys --html", "--html");
  const Result ok = run(m + "--up auto --lock-at auto --frames 0 -q");
  EXPECT_EQ(ok.status, 0) << ok.err;
}

// The picture-quality options and `ibfvs quality` (docs/quality.md).
TEST_F(RenderCommand, QualityOptionsFailCleanly) {
  file("sq.off", kTri);
  file("not-a-png.png", "hello");
  const std::string m = "render sq.off --frames 2 --size 32x32 --out x.png ";
  expect_error(m + "--filter -1", "--filter: must be between 0 and 32 pixels");
  expect_error(m + "--contrast 0.9", "--contrast: must be between 0 (off) and 0.5");
  expect_error(m + "--resample nearest",
               "--resample: expected compensated, cubic or linear, got 'nearest'");
  expect_error(m + "--profile white",
               "--profile: expected square, sawtooth, sine, spike or random");
  expect_error("quality sq.off --warmup 0", "--warmup");
  expect_error("quality --png missing.png", "missing.png");
  expect_error("quality --png not-a-png.png", "not-a-png.png");
  expect_error("quality --png x.png --centre 1", "--centre");
  expect_error("quality missing.off", "missing.off");
  expect_error(m + "--sharpen 5", "--sharpen: must be between 0 (off) and 4");
  expect_error(m + "--sharpen -1", "--sharpen");
  const Result q = run("quality sq.off --size 48x48 --warmup 3");
  EXPECT_EQ(q.status, 0) << q.err;
  EXPECT_NE(q.out.find("alignment A"), std::string::npos) << q.out;
  EXPECT_NE(q.out.find("streak width W"), std::string::npos) << q.out;
  EXPECT_NE(q.out.find("red inflow"), std::string::npos) << q.out;
  // Another tool's picture against a direction-coded picture of the flow:
  // both must be PNGs of one size; the truth must be RGB.
  ASSERT_EQ(run("render sq.off --frames 2 --size 32x32 --out a.png -q").status, 0);
  ASSERT_EQ(run("render sq.off --frames 2 --size 48x48 --out b.png -q").status, 0);
  expect_error("quality --png a.png --direction b.png", "b.png: must be an RGB picture of 32x32");
  expect_error("quality --png a.png --direction missing.png", "missing.png");
  expect_error("quality --png a.png --direction not-a-png.png", "not-a-png.png");
  const Result d = run("quality --png a.png --direction a.png");
  EXPECT_EQ(d.status, 0) << d.err;
  EXPECT_NE(d.out.find("streak width W"), std::string::npos) << d.out;
  // As shown: no red inflow line (the scene's own background).
  const Result shown = run("quality sq.off --size 48x48 --warmup 3 --shown");
  EXPECT_EQ(shown.status, 0) << shown.err;
  EXPECT_EQ(shown.out.find("red inflow"), std::string::npos) << shown.out;
  // --no-image-normalize turns the default off: the summary says so.
  const Result speeds = run(m + "--no-image-normalize");
  EXPECT_EQ(speeds.status, 0) << speeds.err;
  EXPECT_EQ(speeds.out.find("image-normalised"), std::string::npos) << speeds.out;
  EXPECT_NE(speeds.out.find(" (max "), std::string::npos) << speeds.out;
}

TEST_F(RenderCommand, StylesLockingAndTopology) {
  for (const char* style : {"flow", "particles", "principal", "bronze", "eroded", "topology"}) {
    const Result r = run(std::string("render --mesh landscape:2:6:24 --style ") + style +
                         " --size 48x48 --frames 3 --out s.png");
    EXPECT_EQ(r.status, 0) << style << "\n" << r.err;
  }
  // A style's defaults give way to explicit options and to the mesh's own field.
  const Result t =
      run("render --mesh landscape:2:6:24 --style topology --frames 2 --size 32x32 "
          "--out t.png");
  EXPECT_NE(t.out.find("(2 frames, 32x32)"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("gradient:down:0,1,0:normalize"), std::string::npos) << t.out;
  const Result l =
      run("render --mesh landscape:2:6:24 --init random-cells --alpha 0 --lock-at 2 "
          "--lock-camera 30,40,0 --size 32x32 --frames 4 --out l.png -q");
  EXPECT_EQ(l.status, 0) << l.err;
  const std::string m = "render --mesh landscape:2:6:24 --frames 1 --out x.png ";
  // A generated surface's default video name is a plain file name.
  const Result v = run("render --mesh landscape:2:6:24 --size 32x32 --frames 3");
  EXPECT_EQ(v.status, 0) << v.err;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "landscape-2-6-24.mp4")) << v.out;
  // Export (section 3.7): the texture, and the mesh with texture coordinates.
  const Result x =
      run("render --mesh landscape:2:6:24 --style topology --size 48x48 --frames 6 "
          "--lock-at 4 --export topo.obj");
  ASSERT_EQ(x.status, 0) << x.err;
  const TriMesh back = read_mesh(dir_ / "topo.obj");
  EXPECT_EQ(back.vertex_count(), 25u * 25u);
  const std::string obj = test::read_file(dir_ / "topo.obj");
  std::size_t vt = 0, bad = 0;
  for (std::size_t at = obj.find("\nvt "); at != std::string::npos;
       at = obj.find("\nvt ", at + 1)) {
    float u = -1, w = -1;
    std::sscanf(obj.c_str() + at + 4, "%f %f", &u, &w);
    ++vt;
    bad += !(u >= 0 && u <= 1 && w >= 0 && w <= 1);
  }
  EXPECT_EQ(vt, back.vertex_count());
  EXPECT_EQ(bad, 0u);
  EXPECT_NE(test::read_file(dir_ / "topo.mtl").find("map_Kd topo.png"), std::string::npos);
  EXPECT_EQ(read_png(dir_ / "topo.png").width, 48);
  // The same as glTF (JSON + bin + PNG) and GLB (one file), read by tinygltf.
  for (const std::string name : {"topo.gltf", "topo.glb"}) {
    const Result g =
        run("render --mesh landscape:2:6:24 --style topology --size 48x48 "
            "--frames 6 --lock-at 4 -q --export " +
            name);
    ASSERT_EQ(g.status, 0) << g.err;
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    const std::string file = (dir_ / name).string();
    ASSERT_TRUE(name.ends_with(".glb") ? loader.LoadBinaryFromFile(&model, &err, &warn, file)
                                       : loader.LoadASCIIFromFile(&model, &err, &warn, file))
        << err;
    const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
    const tinygltf::Accessor& tex =
        model.accessors.at(static_cast<std::size_t>(prim.attributes.at("TEXCOORD_0")));
    EXPECT_EQ(tex.count, back.vertex_count()) << name;
    const tinygltf::BufferView& view =
        model.bufferViews.at(static_cast<std::size_t>(tex.bufferView));
    std::vector<float> uv(tex.count * 2);
    std::memcpy(uv.data(), model.buffers.at(0).data.data() + view.byteOffset + tex.byteOffset,
                uv.size() * sizeof(float));
    EXPECT_EQ(std::count_if(uv.begin(), uv.end(), [](float c) { return !(c >= 0 && c <= 1); }), 0)
        << name;
    EXPECT_EQ(model.images.at(0).width, 48) << name;
  }
  expect_error(m + "--export topo.ply", "--export: must be a .obj, .gltf, .glb or .vtp file");
  expect_error(m + "--noise-space world", "--noise-space");
  const Result o =
      run("render --mesh landscape:2:6:24 --noise-space object --orbit 2 --size 32x32 "
          "--frames 3 --out o.png -q");
  EXPECT_EQ(o.status, 0) << o.err;
  expect_error(
      m + "--style cartoon",
      "--style: expected flow, crisp, paper, particles, principal, bronze, eroded or topology, "
      "got 'cartoon'");
  expect_error(m + "--init noise", "--init");
  expect_error(m + "--lock-at -5", "--lock-at");
  expect_error(m + "--lock-camera 1,2", "--lock-camera");
  expect_error(m + "--color-by height --color-range p50,p10", "--color-range");
  expect_error(m + "--color-by height --color-range p5,p101", "--color-range");
}

TEST_F(RenderCommand, NanVectorsAreZeroedWithAWarning) {
  TriMesh sq = make_square(1.0f, 2);
  sq.vectors.assign(sq.vertex_count(), glm::vec3(1, 0, 0));
  sq.vectors[4].x = std::nanf("");
  write_ply(sq, dir_ / "v.ply", true);
  const Result r = run("render --mesh v.ply --size 32x32 --frames 2 --out v.png -q");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("v.ply: 1 vectors were NaN or infinite"), std::string::npos) << r.err;
  for (glm::vec3& v : sq.vectors) v = glm::vec3(std::nanf(""));
  write_ply(sq, dir_ / "allnan.ply", false);
  expect_error("render --mesh allnan.ply --frames 2 --out x.png", "allnan.ply");
}

TEST_F(RenderCommand, MalformedMeshesFailCleanly) {
  expect_error("render --mesh missing.off --out x.png", "missing.off: no such file");
  file("empty.off", "");
  expect_error("render --mesh empty.off --out x.png", "empty.off: the file is empty");
  file("trunc.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n");
  expect_error("render --mesh trunc.off --out x.png", "trunc.off: truncated");
  file("counts.off", "OFF\n-3 x 0\n");
  expect_error("render --mesh counts.off --out x.png",
               "counts.off: malformed: OpenMesh's reader stopped at line 2");
  file("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n");
  expect_error("render --mesh index.off --out x.png",
               "index.off: truncated or malformed: a face references a vertex index out of range");
  file("nan.off", "OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n");
  expect_error("render --mesh nan.off --out x.png", "nan.off: line 4 holds a non-finite");
  file("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 inf\n3 0 1 2\n");
  expect_error("render --mesh inf.off --out x.png", "inf.off");
  file("notmesh.off", "#!/bin/sh\necho hello\n");
  expect_error("render --mesh notmesh.off --out x.png",
               "notmesh.off: malformed: OpenMesh's reader stopped");
  file("notmesh.ply", std::string("\x7f"
                                  "ELF\x02\x01\x01\0\0\0",
                                  10));
  expect_error("render --mesh notmesh.ply --out x.png", "notmesh.ply: cannot parse the mesh");
  file("mesh.txt", "1 2 3");
  expect_error("render --mesh mesh.txt --out x.png", "mesh.txt: unknown mesh format");
  file("flat.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n");
  expect_error("render --mesh flat.off --out x.png", "flat.off: every triangle is degenerate");
  file("stl.stl", std::string(84, '\0') + "xx");
  expect_error("render --mesh stl.stl --out x.png", "stl.stl: no faces could be read");
  file("sq.off", kTri);
  expect_error("render --mesh sq.off --field file --out x.png",
               "--field: sq.off: file: the mesh has no per-vertex vectors");
}

TEST_F(RenderCommand, ImpossibleOptionsFailCleanly) {
  file("sq.off", kTri);
  const std::string m = "render --mesh sq.off --frames 1 ";
  expect_error(m + "--alpha 2 --out x.png", "--alpha");
  expect_error(m + "--beta -0.1 --out x.png", "--beta");
  expect_error(m + "--size 0x10 --out x.png", "--size");
  expect_error(m + "--size big --out x.png", "--size");
  expect_error(m + "--scale 0 --out x.png", "--scale");
  expect_error(m + "--profile triangle --out x.png", "--profile");
  expect_error(m + "--field swirl:1 --out x.png", "--field");
  expect_error(m + "--field rotate:0,0,0 --out x.png",
               "--field: the rotation axis must not be zero");
  expect_error(m + "--tangent flat --out x.png", "--tangent");
  expect_error(m + "--image-normalize --dt 0.1 --out x.png", "--image-normalize");
  expect_error(m + "--look-at 1,2 --out x.png", "--look-at");
  expect_error(m + "--field principal:min:smooth=many --out x.png", "smooth=many");
  // Generated shapes: bad parameters name the spec.
  const std::string g = "render --frames 1 --size 16x16 --out x.png --mesh ";
  expect_error(g + "torus:0.3,1", "--mesh: torus:0.3,1: the radii need R > r > 0");
  expect_error(g + "torus:1", "--mesh: torus:1");
  expect_error(g + "torus:1,0.5:2", "expected torus[:R,r]");
  expect_error(g + "cylinder:0,1", "needs RADIUS > 0, LENGTH > 0 and COUNT in 1..16");
  expect_error(g + "cylinder:0.3,1,40", "COUNT in 1..16");
  expect_error(g + "cylinder:1", "expected cylinder[:RADIUS,LENGTH[,COUNT]]");
  const Result t = run(g + "torus:1,0.3 --image-normalize --camera 0,30,0 -q");
  EXPECT_EQ(t.status, 0) << t.err;
  const Result c = run(g + "cylinder:0.2,2,3 --field uniform:1,0,0 -q");
  EXPECT_EQ(c.status, 0) << c.err;
  expect_error(m + "--background 2,0,0 --out x.png", "--background");
  expect_error(m + "--background 0.5,0.5 --out x.png", "--background");
  expect_error(m + "--camera 10,20 --out x.png", "--camera");
  expect_error(m + "--fov 0 --out x.png", "--fov");
  expect_error(m + "--step -1 --out x.png", "--step");
  expect_error(m + "--dt -1 --out x.png", "--dt");
  expect_error(m + "--advect-view next --out x.png", "--advect-view");
  expect_error(m + "--inject mix --out x.png", "--inject");
  expect_error(m + "--subdivide 13 --out x.png", "--subdivide");
  expect_error("render --mesh torus --subdivide 12 --out x.png",
               "--subdivide: torus subdivided 12 times (344 billion triangles) would need about");
  // Images: what memory holds, then what the GL implementation can render.
  expect_error(m + "--size 100000x100000 --out x.png",
               "--size: 100000x100000 pixels would need about 312 GiB of memory; this machine has");
  const test::Result big =
      run(m + "--size 65536x65536 --frames 1 --out big.png", "IBFVS_MEMORY_LIMIT=1000000G");
  EXPECT_EQ(big.status, 1);
  EXPECT_NE(big.err.find("--size: 65536x65536 is larger than this GL implementation's largest "
                         "image"),
            std::string::npos)
      << big.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "big.png"));
  expect_error(m + "--orbit 1000 --out x.png", "--orbit");
  expect_error(m + "--out x.xyz", "--out");
  expect_error(m + "--out nodir/x.png", "nodir");
  expect_error(m + "--out x%d%d.png", "--out");
  expect_error(m + "--out x.png --texture-out t.jpg", "--texture-out");
  expect_error(m + "--out x.png --texture-out nodir/t.png", "--texture-out: the folder 'nodir'");
  expect_error(m + "--surface-color 0.5,0.5,7 --out x.png", "--surface-color");
  expect_error(m + "--fps 0 --out x.mp4", "--fps");
  expect_error(m + "--spike-width 0 --out x.png", "--spike-width");
  expect_error(m + "--vg nan --out x.png", "--vg");
  expect_error(m + "--camera 0,0,-2 --out x.png", "--camera");
  expect_error("render --frames 0 --out x.png", "--frames");
  expect_error("render --frames 99999999999 --out x.png", "--frames");
  // Command-line syntax errors come in the same one-line form.
  expect_error("render --alpha lots --out x.png", "--alpha");
  expect_error("render --seed -1 --out x.png", "--seed");
  expect_error("render --no-such-option", "--no-such-option");
  expect_error("paint", "paint");
  const Result bare = run("");
  EXPECT_EQ(bare.status, 1);
  EXPECT_NE(bare.err.find("render"), std::string::npos) << bare.err;
}

}  // namespace
}  // namespace ibfvs
