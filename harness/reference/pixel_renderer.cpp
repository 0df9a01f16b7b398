#include "harness/reference/pixel_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "harness/reference/progress.h"
#include "harness/util/error.h"
#include "harness/util/interrupt.h"

namespace ldm {
namespace {

// Small enough to balance 2-16 threads on 32x32 test images, large enough that taking a
// tile costs nothing next to its pixels.
constexpr int kTileSize = 16;

void validate_pixel_settings(const PixelRenderSettings& s, int channels) {
  if (s.width <= 0) throw UserError("render: width must be positive");
  if (s.height <= 0) throw UserError("render: height must be positive");
  if (s.spp == 0) throw UserError("render: spp must be at least 1");
  if (s.threads < 0) throw UserError("render: threads must be 0 (all cores) or positive");
  if (channels <= 0) throw UserError("render: channels must be positive");
}

int worker_count(int requested, int tile_count) {
  const int available = std::max(1u, std::thread::hardware_concurrency());
  return std::clamp(requested > 0 ? requested : available, 1, tile_count);
}

int tile_count_of(int width, int height) {
  return ((width + kTileSize - 1) / kTileSize) * ((height + kTileSize - 1) / kTileSize);
}

}  // namespace

int render_worker_count(int threads, int width, int height) {
  return worker_count(threads, tile_count_of(width, height));
}

Image render_pixels(const PixelRenderSettings& settings, int channels,
                    const PixelEstimator& estimator) {
  validate_pixel_settings(settings, channels);
  const int width = settings.width, height = settings.height;
  Image image(width, height, channels);
  const int tiles_x = (width + kTileSize - 1) / kTileSize;
  const int tile_count = tile_count_of(width, height);

  std::atomic<int> next_tile{0};
  std::atomic<int> finished_tiles{0};
  std::atomic<bool> failed{false};
  std::exception_ptr failure;
  std::mutex mutex;  // guards `failure`; with `changed`, wakes the progress loop
  std::condition_variable changed;

  auto render_tile = [&](int tile) {
    const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
    const int x1 = std::min(x0 + kTileSize, width), y1 = std::min(y0 + kTileSize, height);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        // SIGINT/SIGTERM: abandon the image (util/interrupt.h); per pixel, since one tile
        // of a high-spp reference can take minutes. Reading the flag costs nothing.
        throw_if_stop_requested();
        const uint64_t pixel_index = uint64_t(y) * uint64_t(width) + uint64_t(x);
        Pcg32 rng = pixel_stream(settings.seed, settings.pass, pixel_index);
        estimator(x, y, settings.spp, rng, &image.at(x, y, 0));
      }
  };
  auto work = [&] {
    try {
      for (int tile = next_tile++; tile < tile_count && !failed; tile = next_tile++) {
        render_tile(tile);
        {
          std::lock_guard lock(mutex);
          ++finished_tiles;
        }
        changed.notify_one();
      }
    } catch (...) {
      {
        std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        failed = true;
      }
      changed.notify_one();
    }
  };

  std::vector<std::thread> workers;
  const int count = worker_count(settings.threads, tile_count);
  try {
    for (int i = 0; i < count; ++i) workers.emplace_back(work);
  } catch (...) {  // out of threads: stop the ones started (a joinable thread must be joined)
    failed = true;
    for (auto& worker : workers) worker.join();
    throw;
  }

  // The calling thread only reports progress; the workers never touch the terminal.
  ProgressDisplay progress = ProgressDisplay::on_stderr(settings.label, settings.progress);
  {
    std::unique_lock lock(mutex);
    while (finished_tiles < tile_count && !failed) {
      changed.wait_for(lock, std::chrono::milliseconds(100));
      progress.update(double(finished_tiles) / tile_count);
    }
  }
  for (auto& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
  progress.finish();
  return image;
}

PixelRenderSettings reference_render_settings(const std::string& what, int width, int height,
                                              uint32_t spp, uint64_t seed, uint32_t pass,
                                              int threads, bool progress) {
  PixelRenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.spp = spp;
  settings.seed = seed;
  settings.pass = pass;
  settings.threads = threads;
  settings.progress = progress;
  settings.label = what + " reference (seed " + std::to_string(seed) + ", pass " +
                   std::to_string(pass) + ", " + std::to_string(spp) + " spp)";
  return settings;
}

}  // namespace ldm
