// radiance.hpp - what rt::render (renderer.hpp) needs from a scene: the
// camera's rays, and the color each ray brings back (the shaded color of
// stages 05-07, 09 and 10, or a debug image, aov.hpp).
//
//     const rt::radiance_function radiance = rt::make_radiance(s, rt::aov_kind::shaded); // shaded
//     const rt::ray_source rays = rt::camera_rays(s.cam, s.width, s.height);
//     rt::render_result out = rt::render(options, rays, radiance);
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>

#include "../bvh/accelerator.hpp"
#include "../output/aov.hpp"
#include "../camera/camera.hpp"
#include "../shading/dielectric.hpp"
#include "../shading/glossy.hpp"
#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../core/random.hpp"
#include "../camera/ray_image.hpp"
#include "../shading/raytracer.hpp"
#include "renderer.hpp"
#include "sampler.hpp"
#include "../scene/scene.hpp"
#include "../shading/shading.hpp"
#include "../camera/thin_lens.hpp"
#include "../core/vec.hpp"

#include "../bvh/abi_begin.hpp" // RT_BVH_ACCELERATOR_ABI, until bvh/simd_end.hpp

namespace rt {

/// A ray source for rt::render: film position in pixels -> ray.
using ray_source = std::function<ray(real, real)>;
/// A radiance function for rt::render: the color a ray brings back.
using radiance_function = std::function<color(const ray&, sample_context&)>;

/// The camera's rays for a full image of nx x ny pixels (camera.hpp).
inline ray_source camera_rays(const camera& cam, int nx, int ny)
{
    const ray_generator gen = make_ray_generator(cam, nx, ny);
    return [gen](real x, real y) { return generate_ray(gen, x, y); };
}

/// The camera ray of one sample through the thin lens of scene s (stage 10):
/// for a perspective camera with s.lens.aperture > 0, the pinhole ray moved
/// onto a random point of the lens (two numbers drawn from `random`), aimed
/// at the plane in focus; the pinhole ray itself otherwise (nothing drawn).
inline ray lens_ray(const scene& s, const ray& pinhole, pcg32& random)
{
    if (!(s.lens.aperture > 0) || s.cam.kind != projection::perspective)
        return pinhole;
    const frame basis = make_frame(s.cam.eye, s.cam.look_at, s.cam.up);
    const real xi1 = random.next_float(), xi2 = random.next_float();
    return thin_lens_ray(pinhole, basis, s.lens.aperture, s.lens.focus, concentric_disk(xi1, xi2));
}

inline namespace RT_BVH_ACCELERATOR_ABI { // rt::accelerator's (bvh/abi_begin.hpp)

/// An accelerator seen through a counter of the queries made with it, so a
/// render reports its shadow and mirror rays as well as its camera rays. One
/// sample's own counter: it is made per sample, never shared between threads.
struct counting_accelerator {
    const accelerator* accel;
    std::uint64_t* queries;

    bool closest_hit(const ray& r, real tmin, real tmax, hit_record& rec) const
    {
        ++*queries;
        return accel->closest_hit(r, tmin, tmax, rec);
    }
    bool any_hit(const ray& r, real tmin, real tmax) const
    {
        ++*queries;
        return accel->any_hit(r, tmin, tmax);
    }
};

} // namespace RT_BVH_ACCELERATOR_ABI

/// What each sample computes, for scene `s` whose accelerator (stage 04) is
/// `accel`: the shaded color of stages 05-07 (rt::ray_color; rt::ray_color_glass,
/// stage 09, when a material of `s` is a dielectric or a glossy mirror) or a
/// debug image. The shaded color uses the sample's random numbers (stage 10):
/// the thin lens (s.lens, a perspective camera) moves the camera ray's start
/// over the lens, area lights are seen from a random point, glossy mirrors blur.
/// The function refers to `s` and `accel` (it shares ownership of `accel`;
/// `s` must outlive it) and neither may change while a render runs; between
/// renders, what it reads at each call (s.max_depth, the camera and lens,
/// lights, materials) may change, while new shapes need a new accelerator and a
/// first dielectric or glossy mirror a new function. The camera rays must come
/// from s.cam for the thin lens to focus where s.lens says.
inline radiance_function make_radiance(const scene& s, std::shared_ptr<const accelerator> accel, aov_kind aov)
{
    const real unbounded = std::numeric_limits<real>::infinity();
    switch (aov) {
    case aov_kind::rays:
        return [](const ray& r, sample_context&) { return direction_to_color(r.direction); };
    case aov_kind::depth:
        // the distance along the ray, t |d|; 0 where the ray misses
        return [accel, unbounded](const ray& r, sample_context&) {
            hit_record hit;
            return accel->closest_hit(r, 0, unbounded, hit) ? color(float(hit.t * glm::length(r.direction))) : color(0.0f);
        };
    case aov_kind::normal:
        // the unit shading normal mapped to color, (n + 1) / 2; black where the ray misses
        return [accel, unbounded](const ray& r, sample_context&) {
            hit_record hit;
            return accel->closest_hit(r, 0, unbounded, hit) ? color((hit.normal + vec3(1)) * real(0.5)) : color(0.0f);
        };
    case aov_kind::position:
        return [accel, unbounded](const ray& r, sample_context&) {
            hit_record hit;
            return accel->closest_hit(r, 0, unbounded, hit) ? color(hit.point) : color(0.0f);
        };
    case aov_kind::shaded: break;
    }
    const scene* shaded = &s;
    // stage 07's ray color, or stage 09's where the scene has glass or a glossy
    // mirror (at the time of this call)
    const bool glass = has_dielectric(s) || has_glossy(s);
    return [accel, shaded, glass](const ray& pinhole, sample_context& context) {
        std::uint64_t traced = 0;
        const counting_accelerator counted{accel.get(), &traced};
        // stage 10: this sample's random numbers pick its point of the lens, of
        // each area light and its glossy reflections
        shading_options options;
        options.random = &context.rng;
        const ray r = lens_ray(*shaded, pinhole, context.rng);
        const color L =
            glass ? ray_color_glass(*shaded, counted, r, 0, options) : ray_color(*shaded, counted, r, 0, options);
        context.rays += traced - 1; // the camera ray (the first query) is the renderer's own count
        return L;
    };
}

/// The same, building the accelerator of `s` (except for the rays image, which needs none).
inline radiance_function make_radiance(const scene& s, aov_kind aov)
{
    if (aov == aov_kind::rays)
        return make_radiance(s, nullptr, aov);
    // built once, shared by every worker thread (closest_hit and any_hit are const)
    return make_radiance(s, std::make_shared<const accelerator>(s), aov);
}

} // namespace rt

#include "../bvh/simd_end.hpp"
