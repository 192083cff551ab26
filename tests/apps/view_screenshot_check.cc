// SPDX-License-Identifier: Apache-2.0
// Checks a `mrh view` screenshot of scenes/demo_push.xml: not blank, the floor and cubes appear.
//
//   view_screenshot_check IMAGE.png [--panel] [--force]
//
// Exits 0 if every check passes, 1 (printing which failed) otherwise. The scene's colours are
// demo_push.xml's: a light grey floor and a red, a green and a blue cube; lighting shades them,
// so each check looks for a dominant channel rather than an exact value. --panel also requires
// the ImGui panel (its dark background and blue headers). --force also requires the orange
// force arrow (src/viewer/overlay.cc kForceColor, 1.0 0.35 0.1).
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

namespace {

struct Pixel {
  int r, g, b;
};

// Fractions of the image (the window is 1280x800 = 1 024 000 pixels): a cube seen from the
// default camera covers ~1-2 %, the floor most of the rest; 0.1 % is ~1000 pixels.
constexpr double kMinCubeFraction = 0.001;
constexpr double kMinFloorFraction = 0.2;
// The force arrow is thin: 0.01 % is ~100 pixels, a few millimetres of shaft at the default view.
constexpr double kMinArrowFraction = 0.0001;
// The panel region is mostly background, with text, buttons and plots on it.
constexpr double kMinPanelFraction = 0.5;
// Under the panel the view shows floor; a few dark pixels are shadows.
constexpr double kMaxDarkBelowPanel = 0.1;
// A blank (single-colour) frame has zero spread; a rendered scene has shading everywhere.
constexpr double kMinLumaStdDev = 10.0;

struct Check {
  std::string name;
  std::function<bool(const Pixel&)> matches;
  double min_fraction;
};

// Fraction of near-black neutral pixels (ImGui's dark window background) in the band
// x < 20 % of the width, y0 < y < y1 (fractions of the height).
double DarkFraction(const std::vector<Pixel>& pixels, int width, int height, double y0, double y1) {
  std::size_t dark = 0, total = 0;
  for (int y = static_cast<int>(y0 * height); y < static_cast<int>(y1 * height); ++y) {
    for (int x = 0; x < width / 5; ++x) {
      const Pixel& p = pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                              static_cast<std::size_t>(x)];
      dark += (p.r < 60 && p.g < 60 && p.b < 60 && std::abs(p.r - p.b) < 12) ? 1 : 0;
      ++total;
    }
  }
  return total == 0 ? 0.0 : static_cast<double>(dark) / static_cast<double>(total);
}

double LumaStdDev(const std::vector<Pixel>& pixels) {
  double sum = 0.0, sum2 = 0.0;
  for (const Pixel& p : pixels) {
    const double y = 0.299 * p.r + 0.587 * p.g + 0.114 * p.b;
    sum += y;
    sum2 += y * y;
  }
  const double n = static_cast<double>(pixels.size());
  const double mean = sum / n;
  return std::sqrt(std::max(0.0, sum2 / n - mean * mean));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: view_screenshot_check IMAGE.png [--panel] [--force]\n");
    return 2;
  }
  bool panel = false, force = false;
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "--panel") == 0) {
      panel = true;
    } else if (std::strcmp(argv[i], "--force") == 0) {
      force = true;
    } else {
      std::fprintf(stderr, "view_screenshot_check: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  int width = 0, height = 0, channels = 0;
  unsigned char* data = stbi_load(argv[1], &width, &height, &channels, 3);
  if (data == nullptr) {
    std::fprintf(stderr, "FAIL: cannot read %s: %s\n", argv[1], stbi_failure_reason());
    return 1;
  }
  std::vector<Pixel> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    pixels[i] = Pixel{data[3 * i], data[3 * i + 1], data[3 * i + 2]};
  }
  stbi_image_free(data);

  std::vector<Check> checks = {
      {"light grey floor",
       [](const Pixel& p) {
         return p.r > 150 && std::abs(p.r - p.g) < 20 && std::abs(p.g - p.b) < 20;
       },
       kMinFloorFraction},
      {"red cube",
       [](const Pixel& p) {
         return p.r > 100 && p.r > p.g + 50 && p.r > p.b + 50;
       },
       kMinCubeFraction},
      {"green cube",
       [](const Pixel& p) {
         return p.g > 100 && p.g > p.r + 40 && p.g > p.b + 30;
       },
       kMinCubeFraction},
      {"blue cube",
       [](const Pixel& p) {
         return p.b > 100 && p.b > p.r + 50 && p.b > p.g + 30;
       },
       kMinCubeFraction},
  };

  if (force) {
    // Orange against the red cube (0.8 0.3 0.2): both have g ≈ 0.35 r, but the arrow's blue is
    // under half its green (0.29 shaded) and the cube's two thirds of it. The yellow pointer
    // (0.95 0.8 0.1) has g > 0.8 r.
    checks.push_back({"orange force arrow",
                      [](const Pixel& p) {
                        return p.r > 90 && 4 * p.g > p.r && 2 * p.g < p.r && 20 * p.b < 9 * p.g;
                      },
                      kMinArrowFraction});
  }

  int failures = 0;
  const double stddev = LumaStdDev(pixels);
  std::printf("%s: %dx%d, luma std dev %.1f\n", argv[1], width, height, stddev);
  if (stddev < kMinLumaStdDev) {
    std::fprintf(stderr, "FAIL: the image is blank (luma std dev %.1f < %.1f)\n", stddev,
                 kMinLumaStdDev);
    ++failures;
  }
  for (const Check& check : checks) {
    std::size_t count = 0;
    for (const Pixel& p : pixels) count += check.matches(p) ? 1 : 0;
    const double fraction = static_cast<double>(count) / static_cast<double>(pixels.size());
    std::printf("%-24s %8zu pixels (%.2f %%)\n", check.name.c_str(), count, 100.0 * fraction);
    if (fraction < check.min_fraction) {
      std::fprintf(stderr, "FAIL: %s covers %.3f %% of the image; expected >= %.3f %%\n",
                   check.name.c_str(), 100.0 * fraction, 100.0 * check.min_fraction);
      ++failures;
    }
  }
  if (panel) {
    // The panel is docked at the top left, over what is otherwise floor (below the dark sky):
    // most of the band 20-40 % down must be the panel's near-black, neutral background.
    const double fraction = DarkFraction(pixels, width, height, 0.2, 0.4);
    std::printf("%-24s %.2f %% of its region\n", "ImGui panel", 100.0 * fraction);
    if (fraction < kMinPanelFraction) {
      std::fprintf(stderr, "FAIL: the panel region is %.1f %% panel-dark; expected >= %.1f %%\n",
                   100.0 * fraction, 100.0 * kMinPanelFraction);
      ++failures;
    }
    // It stays compact: the band 60-90 % down, under it, is floor.
    const double below = DarkFraction(pixels, width, height, 0.6, 0.9);
    std::printf("%-24s %.2f %% panel-dark\n", "below the panel", 100.0 * below);
    if (below > kMaxDarkBelowPanel) {
      std::fprintf(stderr,
                   "FAIL: %.1f %% of the band below the panel is panel-dark; expected <= %.1f %% "
                   "(the panel covers too much of the view)\n",
                   100.0 * below, 100.0 * kMaxDarkBelowPanel);
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}
