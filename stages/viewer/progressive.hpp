// progressive.hpp - the viewer's render loop: rt::render driven in passes on a
// worker thread, restartable at any moment (no SDL here).
//
// A view (camera, image size, debug view, sampler, samples, depth, filter,
// seed) is rendered as a sequence of levels:
//   1. a coarse preview: one ray through the centre of each block of
//      coarse_factor x coarse_factor pixels (an image coarse_factor times
//      smaller whose film positions are scaled up to the full image's, box
//      filtered), shown as blocks;
//   2. the full image at 1 sample per pixel, then 4, 16, ... up to the
//      view's samples per pixel, each level rendered in bands of rows that
//      replace the previous level's rows as they finish.
// Every full-resolution level is the image stage08_output writes for the same
// settings and that sample count, bit for bit: a band is an rt::render of a
// crop, and a crop holds exactly the full render's pixels (renderer.hpp).
// Nothing here computes a color: the radiance function comes from
// rt::make_radiance (render_setup.hpp), as in stage08_output, or, in the
// path-traced view, from stage 11's rt::path_radiance (path_radiance_of):
// each level then averages more paths, so the image refines as it does for samples.
//
// Restarting: start() bumps a generation counter. The radiance function is
// wrapped so that every sample first compares the counter with its render's;
// a stale render throws `cancelled`, which rt::render passes on after its
// threads stop (within one tile), and the worker starts the newest view.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/camera/camera.hpp>
#include <rt/core/error.hpp>
#include <rt/rendering/filter.hpp>
#include <rt/path_tracing/emitters.hpp>
#include <rt/core/image.hpp>
#include <rt/path_tracing/path_tracer.hpp>
#include <rt/rendering/render_setup.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/rendering/sampler.hpp>
#include <rt/scene/scene.hpp>

namespace viewer {

/// Everything that decides the image.
struct view {
    rt::camera cam;
    int width = 640, height = 480;
    rt::aov_kind aov = rt::aov_kind::shaded;
    std::optional<rt::sampler_kind> sampler;  ///< none: rt::default_sampler of each level's spp
    int samples_per_pixel = 1;                ///< the last level's
    int max_depth = 5;
    bool path_traced = false;  ///< stage 11's path tracer (MIS, roulette) instead of the shaded color
    rt::filter reconstruction{};
    std::uint64_t seed = 0;
    int threads = 0;
};

/// The preview's block size in pixels.
constexpr int coarse_factor = 8;

/// One pass: the coarse preview (samples_per_pixel 0) or a full image.
struct level {
    int samples_per_pixel = 0;  ///< asked for; 0 for the coarse preview
    rt::sampler_kind sampler = rt::sampler_kind::center;
    bool coarse() const { return samples_per_pixel == 0; }
};

/// The levels of a view: the preview, then 1, 4, 16, ... samples per pixel up
/// to the view's count (a level that would give the same effective count as
/// the one before it is left out, e.g. every level after 1 for the centre sampler).
inline std::vector<level> plan_levels(const view& v)
{
    std::vector<level> levels{level{}};
    const int target = std::max(1, v.samples_per_pixel);
    int previous_effective = 0;
    for (int spp = 1;; spp = std::min(spp * 4, target)) {
        const rt::sampler_kind kind = v.sampler.value_or(rt::default_sampler(spp));
        const int effective = rt::effective_samples(kind, spp);
        if (effective != previous_effective || spp == target) {
            if (effective == previous_effective) // same count as the level before: the target replaces it
                levels.pop_back();
            levels.push_back(level{spp, kind});
            previous_effective = effective;
        }
        if (spp == target)
            break;
    }
    return levels;
}

/// The options of a full-resolution level: what stage08_output builds from
/// --width, --height, --spp, --sampler, --filter, --filter-radius, --threads, --seed.
inline rt::render_options level_options(const view& v, const level& l)
{
    rt::render_options o;
    o.width = v.width;
    o.height = v.height;
    o.samples_per_pixel = l.coarse() ? 1 : l.samples_per_pixel;
    o.sampler = l.sampler;
    o.reconstruction = v.reconstruction;
    o.threads = v.threads;
    o.seed = v.seed;
    return o;
}

/// What the worker is doing, for the window title.
struct status {
    std::uint64_t generation = 0;  ///< of the view this status describes
    rt::aov_kind aov = rt::aov_kind::shaded;  ///< of that view
    int levels_done = 0;           ///< the coarse preview counts as one
    int levels_total = 0;
    int samples_per_pixel = 0;     ///< effective, of the level in progress (or the last one)
    double level_fraction = 0;     ///< of the level in progress, by rows
    std::uint64_t rays = 0;        ///< since the view started
    double seconds = 0;            ///< since the view started (until it finished)
    bool finished = false;         ///< every level done
    std::string error;             ///< why the render stopped, if it failed
};

/// A finished full-resolution level, as stage08_output would write it.
struct completed_image {
    rt::image pixels;
    view settings;
    level pass;
    std::uint64_t generation = 0;
};

/// Makes the radiance function of a debug view for the worker's scene.
using radiance_factory = std::function<rt::radiance_function(const rt::scene&, rt::aov_kind)>;

/// rt::make_radiance, with the scene's accelerator built on first need and
/// kept for every later view (the shapes never change; the views share it).
inline radiance_factory library_radiance()
{
    auto accel = std::make_shared<std::shared_ptr<const rt::accelerator>>();
    return [accel](const rt::scene& s, rt::aov_kind aov) {
        if (aov != rt::aov_kind::rays && !*accel)
            *accel = std::make_shared<const rt::accelerator>(s);
        return rt::make_radiance(s, *accel, aov);
    };
}

/// Stage 11's path tracer as a radiance function for `s` (which must outlive
/// it): MIS, Russian roulette, the scene's glowing triangles and background;
/// each sample's path draws from the sample's own generator.
inline rt::radiance_function path_radiance_of(const rt::scene& s)
{
    auto accel = std::make_shared<const rt::accelerator>(s);
    auto lights = std::make_shared<const rt::emitter_list>(rt::find_emitters(s));
    const rt::scene* scene = &s;
    return [accel, lights, scene](const rt::ray& r, rt::sample_context& ctx) {
        return rt::path_radiance(*scene, *accel, *lights, r, ctx.rng, rt::path_options{},
                                 rt::ray_count_observer{&ctx.rays});
    };
}

class progressive_renderer {
public:
    /// Takes the scene (the worker thread alone reads it from now on).
    explicit progressive_renderer(rt::scene scene, radiance_factory factory = library_radiance())
        : scene_(std::move(scene)), factory_(std::move(factory)), worker_([this] { work(); })
    {
    }

    progressive_renderer(const progressive_renderer&) = delete;
    progressive_renderer& operator=(const progressive_renderer&) = delete;

    /// Stops the render in progress (within a tile) and joins the worker.
    ~progressive_renderer()
    {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            quit_ = true;
            generation_.fetch_add(1);
        }
        wake_.notify_all();
        worker_.join();
    }

    /// Cancels whatever is rendering and starts `v`; returns its generation.
    std::uint64_t start(const view& v)
    {
        std::uint64_t generation = 0;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            pending_ = v;
            generation = generation_.fetch_add(1) + 1;
        }
        wake_.notify_all();
        return generation;
    }

    /// The generation of the newest view start() was given.
    std::uint64_t generation() const { return generation_.load(); }

    /// Copies the rows of the displayed image that changed since the last call
    /// into `out` (resized to the view's size when that changed) and returns
    /// them as [y0, y1) (empty when nothing changed), with the status at that moment.
    std::pair<int, int> take(rt::image& out, status& now)
    {
        std::lock_guard<std::mutex> lock(mutex_);
        now = status_;
        if (out.width != shown_.width || out.height != shown_.height) {
            out = shown_;
            dirty_begin_ = dirty_end_ = 0;
            return {0, shown_.height};
        }
        const std::pair<int, int> rows{dirty_begin_, dirty_end_};
        for (int y = dirty_begin_; y < dirty_end_; ++y)
            std::copy_n(&shown_.at(0, y), std::size_t(shown_.width), &out.at(0, y));
        dirty_begin_ = dirty_end_ = 0;
        return rows;
    }

    /// The last finished full-resolution level of the newest view, if there is one.
    std::optional<completed_image> completed() const
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!completed_ || completed_->generation != generation_.load())
            return std::nullopt;
        return completed_;
    }

private:
    struct cancelled {};

    void work()
    {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            wake_.wait(lock, [&] { return quit_ || pending_.has_value(); });
            if (quit_)
                return;
            const view v = *pending_;
            pending_.reset();
            const std::uint64_t generation = generation_.load();
            status_ = status{};
            status_.generation = generation;
            status_.aov = v.aov;
            lock.unlock();
            run(v, generation);
            lock.lock();
        }
    }

    /// Renders every level of `v` unless a newer view arrives.
    void run(const view& v, std::uint64_t generation)
    {
        const auto start = std::chrono::steady_clock::now();
        auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
        std::uint64_t rays_before = 0; // rays of the finished renders of this view
        try {
            if (!radiance_ || radiance_aov_ != v.aov || radiance_path_ != v.path_traced) {
                radiance_ = nullptr;
                radiance_ = v.path_traced ? path_radiance_of(scene_) : factory_(scene_, v.aov);
                radiance_aov_ = v.aov;
                radiance_path_ = v.path_traced;
            }
            scene_.max_depth = v.max_depth; // no render is running: the worker is here
            scene_.cam = v.cam;              // the thin lens (stage 10) focuses along the view's camera
            const rt::radiance_function& radiance = radiance_;
            auto guarded = [&](const rt::ray& r, rt::sample_context& ctx) {
                if (generation_.load(std::memory_order_relaxed) != generation)
                    throw cancelled{};
                return radiance(r, ctx);
            };
            const std::vector<level> levels = plan_levels(v);
            publish([&](status& s) { s.levels_total = int(levels.size()); });
            rt::image current(v.width, v.height);
            for (const level& l : levels) {
                rt::render_options options = level_options(v, l);
                const int spp = rt::effective_samples(options.sampler, options.samples_per_pixel);
                publish([&](status& s) {
                    s.samples_per_pixel = spp;
                    s.level_fraction = 0;
                });
                auto progress = [&](const rt::render_progress& p) {
                    publish([&](status& s) {
                        s.rays = rays_before + p.rays;
                        s.seconds = seconds();
                    });
                };
                if (l.coarse()) {
                    // the film positions of a coarse_factor times smaller image, scaled to the full one's
                    options.width = (v.width + coarse_factor - 1) / coarse_factor;
                    options.height = (v.height + coarse_factor - 1) / coarse_factor;
                    options.reconstruction = rt::filter{}; // each block shows its own ray, unfiltered
                    const rt::ray_source full = rt::camera_rays(v.cam, v.width, v.height);
                    const rt::real f = rt::real(coarse_factor);
                    auto rays = [&](rt::real x, rt::real y) { return full(x * f, y * f); };
                    const rt::render_result preview = rt::render(options, rays, guarded, progress);
                    rays_before += preview.stats.camera_rays + preview.stats.extra_rays;
                    blow_up(preview.pixels, current);
                    publish_rows(current, 0, v.height, generation);
                } else {
                    const rt::ray_source rays = rt::camera_rays(v.cam, v.width, v.height);
                    // bands of whole tiles, at least 4 tiles per thread where the width allows
                    const int tile = options.tile_size;
                    const int tiles_across = (v.width + tile - 1) / tile;
                    const int wanted = 4 * rt::thread_count(v.threads);
                    const int band = tile * std::max(1, (wanted + tiles_across - 1) / tiles_across);
                    for (int y0 = 0; y0 < v.height; y0 += band) {
                        const int y1 = std::min(v.height, y0 + band);
                        options.crop = rt::crop_window{0, v.width, y0, y1};
                        const rt::render_result part = rt::render(options, rays, guarded, progress);
                        rays_before += part.stats.camera_rays + part.stats.extra_rays;
                        rt::paste(current, part.pixels, 0, y0);
                        publish_rows(current, y0, y1, generation);
                        publish([&](status& s) { s.level_fraction = double(y1) / double(v.height); });
                    }
                    std::lock_guard<std::mutex> lock(mutex_);
                    completed_ = completed_image{current, v, l, generation};
                }
                publish([&](status& s) {
                    ++s.levels_done;
                    s.rays = rays_before;
                    s.seconds = seconds();
                });
            }
            publish([&](status& s) { s.finished = true; });
        } catch (const cancelled&) {
            // a newer view is waiting
        } catch (const std::exception& e) {
            const std::string message = e.what();
            publish([&](status& s) {
                s.error = message;
                s.seconds = seconds();
            });
        }
    }

    /// Each pixel of `full` takes the value of the preview pixel whose block holds its centre.
    static void blow_up(const rt::image& preview, rt::image& full)
    {
        // rows count from the top, film positions from the bottom: the preview's
        // bottom row starts at the full image's film y = 0
        for (int y = 0; y < full.height; ++y) {
            const int film_row = full.height - 1 - y;
            const int preview_row = preview.height - 1 - film_row / coarse_factor;
            for (int x = 0; x < full.width; ++x)
                full.at(x, y) = preview.at(x / coarse_factor, preview_row);
        }
    }

    template <class Change>
    void publish(Change&& change)
    {
        std::lock_guard<std::mutex> lock(mutex_);
        change(status_);
    }

    /// Makes rows [y0, y1) of `current` the displayed ones (unless the view is stale).
    void publish_rows(const rt::image& current, int y0, int y1, std::uint64_t generation)
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (generation_.load() != generation)
            return;
        if (shown_.width != current.width || shown_.height != current.height) {
            shown_ = current;
            dirty_begin_ = 0;
            dirty_end_ = current.height;
            return;
        }
        for (int y = y0; y < y1; ++y)
            std::copy_n(&current.at(0, y), std::size_t(current.width), &shown_.at(0, y));
        if (dirty_begin_ == dirty_end_) {
            dirty_begin_ = y0;
            dirty_end_ = y1;
        } else {
            dirty_begin_ = std::min(dirty_begin_, y0);
            dirty_end_ = std::max(dirty_end_, y1);
        }
    }

    // the worker's own (read by the render threads during a render)
    rt::scene scene_;
    radiance_factory factory_;
    rt::radiance_function radiance_;
    rt::aov_kind radiance_aov_ = rt::aov_kind::shaded;
    bool radiance_path_ = false;

    // shared, under mutex_ (generation_ is also read without it)
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::atomic<std::uint64_t> generation_{0};
    std::optional<view> pending_;
    bool quit_ = false;
    status status_;
    rt::image shown_;
    int dirty_begin_ = 0, dirty_end_ = 0;
    std::optional<completed_image> completed_;

    std::thread worker_;  // last: it starts after everything above exists
};

} // namespace viewer
