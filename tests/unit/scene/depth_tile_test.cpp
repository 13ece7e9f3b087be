// Depth tiles (sharded sealing): a tile of the depth image holds the whole image's pixels bit for
// bit, whatever the layout of the tiles, and a tile renderer does only about its share of the work
// (the rasteriser's counters: leaves and triangles visited, not time).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "analytic_scenes.hpp"
#include "climbsim/errors.hpp"
#include "render_scene.hpp"

namespace climbsim::scene {
namespace {

using testing::pose;

// A rough wall of pixel-sized and of several-pixel triangles (both of the kernel's paths) with
// a groove and a step, in the world as a pylon face, and a box standing on it as a moving body.
struct TileScene {
  RenderScene scene;
  Pose T_W_F;
  explicit TileScene(double spacing_m)
      : scene(mesh(spacing_m)), T_W_F(pose(3.2, -1.7, 2.4, 90.0, 0.0, 0.0) * pose(0, 0, 0, 0, 0, 180.0)) {
    scene.addBody(testing::box({-0.02, -0.03, -0.01}, {0.05, 0.04, 0.02}, 7), T_W_F * pose(0.11, -0.07, 0.0, 0, 0, 25.0));
  }
  static TriangleMesh mesh(double spacing_m) {
    testing::AnalyticWall wall = testing::refined(testing::vGroove(), spacing_m, 0.7);
    const auto groove = wall.height_m;
    wall.height_m = [groove](double x, double y) { return groove(x, y) + 0.002 * x - 0.003 * y + (y > 0.1 ? 0.004 : 0.0); };
    TriangleMesh out;
    testing::appendMesh(out, testing::meshWall(wall), pose(3.2, -1.7, 2.4, 90.0, 0.0, 0.0) * pose(0, 0, 0, 0, 0, 180.0));
    return out;
  }
};

DepthImage render(RenderScene& scene, const Pose& T_W_C, DepthCameraParams camera, const PixelTile& tile) {
  camera.tile = tile;
  DepthImage image;
  scene.renderDepth(T_W_C, camera, {}, image);
  return image;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// rows x cols tiles covering the image (the last ones take the remainder).
std::vector<PixelTile> grid(const DepthCameraParams& camera, int rows, int cols) {
  std::vector<PixelTile> tiles;
  const int h = camera.height_px / rows, w = camera.width_px / cols;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      tiles.push_back({i * h, j * w, i + 1 == rows ? camera.height_px - i * h : h,
                       j + 1 == cols ? camera.width_px - j * w : w});
    }
  }
  return tiles;
}

TEST(DepthTiles, EveryTileOfEveryLayoutHoldsTheWholeImagesPixelsBitForBit) {
  // 3 mm triangles under 256 px of 3.1 mm (about a pixel each) and under 800 px of 1 mm (several
  // pixels each, as the 1024 px camera on the pylon's 5 mm grid).
  for (const auto& [spacing_m, px] : {std::pair{0.0031, 256}, std::pair{0.0051, 800}}) {
    TileScene s(spacing_m);
    DepthCameraParams camera;
    camera.width_px = px;
    camera.height_px = px - 37;  // not square, not a multiple of the tiles
    camera.pixel_size_m = 0.8 / px;
    for (const Pose& T_F_C : {pose(0.013, -0.021, 0.0, 0, 0, 0), pose(0.017, 0.009, 0.004, 3.0, -2.0, 20.0)}) {
      const Pose T_W_C = s.T_W_F * T_F_C;
      const DepthImage whole = render(s.scene, T_W_C, camera, {});
      std::vector<PixelTile> tiles;
      for (const auto& [rows, cols] : {std::pair{2, 1}, std::pair{1, 2}, std::pair{3, 3}, std::pair{4, 1}}) {
        for (const PixelTile& t : grid(camera, rows, cols)) tiles.push_back(t);
      }
      // Overlapping boxes as the shards' (halo), a single row, column and pixel, the corners.
      tiles.push_back({0, 0, camera.height_px / 2 + 31, camera.width_px});
      tiles.push_back({camera.height_px / 2 - 29, 0, camera.height_px - (camera.height_px / 2 - 29), camera.width_px});
      tiles.push_back({17, 0, 1, camera.width_px});
      tiles.push_back({0, 101, camera.height_px, 1});
      tiles.push_back({camera.height_px - 1, camera.width_px - 1, 1, 1});
      tiles.push_back({5, 3, 1, 1});
      for (const PixelTile& t : tiles) {
        const DepthImage part = render(s.scene, T_W_C, camera, t);
        ASSERT_EQ(part.tile, t);
        for (int r = t.row0; r < t.row0 + t.rows; ++r) {
          for (int c = t.col0; c < t.col0 + t.cols; ++c) {
            ASSERT_TRUE(sameBits(whole.at(r, c), part.at(r, c)))
                << px << " px, tile rows " << t.row0 << "+" << t.rows << " cols " << t.col0 << "+" << t.cols
                << ", pixel " << r << "," << c << ": " << whole.at(r, c) << " vs " << part.at(r, c);
          }
        }
      }
    }
  }
}

TEST(DepthTiles, ATileVisitsAboutItsShareOfTheLeavesAndTriangles) {
  TileScene s(0.0051);
  DepthCameraParams camera;
  camera.width_px = 800;
  camera.height_px = 800;
  camera.pixel_size_m = 0.001;
  const Pose T_W_C = s.T_W_F * pose(0.017, 0.009, 0.0, 0, 0, 20.0);
  render(s.scene, T_W_C, camera, {});
  const RasterCounters whole = s.scene.lastDepthCounters();
  ASSERT_GT(whole.triangles, 40000u);  // 0.8 m x 0.8 m of 5 mm cells: about 51 000 under the camera
  RasterCounters quarters;
  for (const PixelTile& t : grid(camera, 2, 2)) {
    render(s.scene, T_W_C, camera, t);
    const RasterCounters tile = s.scene.lastDepthCounters();
    // A quarter of the pixels: a quarter of the work, and a rim of leaves (40 mm) met by two tiles.
    EXPECT_LT(tile.triangles, 0.32 * whole.triangles) << "tile " << t.row0 << "," << t.col0;
    EXPECT_LT(tile.leaves, 0.32 * whole.leaves) << "tile " << t.row0 << "," << t.col0;
    quarters += tile;
  }
  // Together no less than the whole (every triangle under the image is in some tile).
  EXPECT_GE(quarters.triangles, whole.triangles);
  EXPECT_LT(quarters.triangles, 1.4 * whole.triangles);
}

// A tile with a mask (a sealing shard's pixels): the mask's pixels as in the whole image, far at
// the tile's others, and only the leaves near the mask are visited.
TEST(DepthTiles, AMaskedTileRendersItsMaskAsTheWholeImageFarElsewhereAndVisitsLess) {
  for (const auto& [spacing_m, px] : {std::pair{0.0031, 256}, std::pair{0.0051, 800}}) {
    TileScene s(spacing_m);
    DepthCameraParams camera;
    camera.width_px = px;
    camera.height_px = px;
    camera.pixel_size_m = 0.8 / px;
    const Pose T_W_C = s.T_W_F * pose(0.017, 0.009, 0.004, 3.0, -2.0, 20.0);
    const DepthImage whole = render(s.scene, T_W_C, camera, {});
    // An annulus strip of a quarter of the image's width (a sealing strip) and a few loose pixels.
    std::vector<std::uint32_t> pixels;
    for (int r = 0; r < px; ++r) {
      for (int c = 0; c < px; ++c) {
        const double d = std::hypot(r - 0.5 * px, c - 0.5 * px) / px;
        if ((d > 0.30 && d < 0.36 && c < 0.7 * px) || (r * 7 + c * 3) % 9973 == 0) {
          pixels.push_back(static_cast<std::uint32_t>(r * px + c));
        }
      }
    }
    PixelTile t{px / 10, px / 20, px - px / 10 - 3, px - px / 20 - 1, nullptr};
    t.mask = std::make_shared<const PixelMask>(px, px, pixels);
    const DepthImage part = render(s.scene, T_W_C, camera, t);
    const RasterCounters masked = s.scene.lastDepthCounters();
    PixelTile box = t;
    box.mask.reset();
    render(s.scene, T_W_C, camera, box);
    const RasterCounters unmasked = s.scene.lastDepthCounters();
    for (int r = t.row0; r < t.row0 + t.rows; ++r) {
      for (int c = t.col0; c < t.col0 + t.cols; ++c) {
        const float expected = t.mask->contains(r, c) ? whole.at(r, c) : static_cast<float>(camera.far_m);
        ASSERT_TRUE(sameBits(expected, part.at(r, c)))
            << px << " px, pixel " << r << "," << c << " (in mask " << t.mask->contains(r, c) << "): " << whole.at(r, c)
            << " vs " << part.at(r, c);
      }
    }
    // The strip covers about 0.15 of the image; with the loose pixels' blocks, well under the box.
    EXPECT_LT(masked.triangles, 0.75 * unmasked.triangles) << px << " px";
    EXPECT_LT(masked.leaves, 0.75 * unmasked.leaves) << px << " px";
  }
}

// PixelMask on an image whose rows span several words (the last one not full): its row runs and
// its 2 x 2 quads are its pixels; meets tells exactly whether a box of pixels (clipped to the
// image) holds one of them, for boxes within a word, across words, over whole rows and reaching
// out of the image; mayMeet never says no where it does.
TEST(DepthTiles, AMasksPixelTestTellsExactlyWhetherABoxHoldsOneOfItsPixels) {
  const int W = 150, H = 40;
  std::vector<std::uint32_t> pixels;
  for (int r = 0; r < H; ++r) {
    for (int c = 0; c < W; ++c) {
      if ((r * 37 + c * 11) % 101 == 0 || c == 63 || c == 64 || (r == 7 && c > 120)) {
        pixels.push_back(static_cast<std::uint32_t>(r * W + c));
      }
    }
  }
  const PixelMask mask(W, H, pixels);
  // Its row runs: maximal, in raster order, exactly its pixels.
  std::vector<char> from_runs(static_cast<std::size_t>(W) * H, 0);
  std::uint32_t previous_end = 0;
  for (const PixelMask::Run& run : mask.runs()) {
    ASSERT_GE(run.raster, previous_end);
    ASSERT_GT(run.length, 0u);
    const int r = static_cast<int>(run.raster) / W, c = static_cast<int>(run.raster) % W;
    ASSERT_LE(c + static_cast<int>(run.length), W);
    ASSERT_FALSE(c > 0 && mask.contains(r, c - 1)) << "run at " << r << "," << c << " not maximal";
    ASSERT_FALSE(c + static_cast<int>(run.length) < W && mask.contains(r, c + static_cast<int>(run.length)));
    for (std::uint32_t k = 0; k < run.length; ++k) from_runs[run.raster + k] = 1;
    previous_end = run.raster + run.length;
  }
  // Its quads: bit 2 dr + dc where pixel (r + dr, c + dc) is in it.
  for (int r = 0; r < H; ++r) {
    for (int c = 0; c < W; ++c) {
      ASSERT_EQ(from_runs[static_cast<std::size_t>(r) * W + c] != 0, mask.contains(r, c)) << r << "," << c;
      unsigned quad = 0;
      for (int d = 0; d < 4; ++d) {
        const int rr = r + d / 2, cc = c + d % 2;
        quad |= rr < H && cc < W && mask.contains(rr, cc) ? 1u << d : 0u;
      }
      ASSERT_EQ(mask.quads()[static_cast<std::size_t>(r) * W + c], quad) << r << "," << c;
    }
  }
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> row(-3, H + 2), col(-3, W + 2), size(0, 70);
  int met = 0;
  for (int k = 0; k < 20000; ++k) {
    const int r0 = row(rng), c0 = col(rng);
    const int r1 = r0 + size(rng) / 8, c1 = c0 + size(rng);
    bool expected = false;
    for (int r = std::max(r0, 0); r <= std::min(r1, H - 1); ++r) {
      for (int c = std::max(c0, 0); c <= std::min(c1, W - 1); ++c) expected = expected || mask.contains(r, c);
    }
    ASSERT_EQ(mask.meets(r0, r1, c0, c1), expected) << "rows " << r0 << ".." << r1 << ", columns " << c0 << ".." << c1;
    if (expected) {
      ASSERT_TRUE(mask.mayMeet(r0, r1, c0, c1));
    }
    met += expected;
  }
  EXPECT_GT(met, 2000);
  EXPECT_LT(met, 18000);
}

TEST(DepthTiles, AMaskOfAnotherSizeIsRefusedNamingIt) {
  DepthCameraParams camera;
  camera.tile = PixelTile{0, 0, 10, 10, std::make_shared<const PixelMask>(128, 256, std::vector<std::uint32_t>{5})};
  try {
    camera.validate();
    FAIL() << "a 128 x 256 mask on a 256 x 256 image was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("tile.mask = 128 x 256 px"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace climbsim::scene
