// edge.hpp - stage 02's picture of sampling: one edge, 1 and 16 samples per pixel.
//
// The edge: the plane through the eye e that holds the view direction -w and
// is tilted by 20 degrees from the camera's horizontal u-w plane. A sample's
// value is 1 where its ray runs above that plane, else 0: with n = cos(20) v
// - sin(20) u and the point r(1) = o + d of the ray,
//     value = 1  if  (r(1) - e) . n >= 0.
// For both projections r(1) - e = u u + v v - c w (c = d or 1, eq. 4.1 and
// FCG 4th ed., sec. 4.3.1-4.3.2), so the test is v cos(20) - u sin(20) >= 0:
// in the image a straight edge through the window's centre, rising 20 degrees
// to the right (on the window; the pixels may stretch it).
//
// The exact value of a pixel is the fraction of its square [i, i + 1] x
// [j, j + 1] on the bright side, the area of the square clipped by the
// half-plane (one step of Sutherland-Hodgman clipping: I. E. Sutherland,
// G. W. Hodgman, "Reentrant polygon clipping", CACM 17(1), 1974), measured by
// the shoelace formula. The program prints the RMS difference between the
// estimates and these exact values over the pixels the edge crosses.
//
// Used by stage02_generate_rays (--edge) and by tests/docs_figures.cpp (the
// figures the stage page quotes). It calls the student's stage-02 exercises.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <rt/camera/camera.hpp>
#include <rt/core/image.hpp>
#include <rt/camera/pixel_sampling.hpp>
#include <rt/core/random.hpp>
#include <rt/core/vec.hpp>

namespace stage {

/// The seed and the generator stream of the edge pictures' samples.
constexpr std::uint64_t edge_seed = 1;
constexpr std::uint64_t edge_stream = 2;

/// The edge's tilt: cos and sin of 20 degrees.
constexpr double edge_cos = 0.93969262078590838;
constexpr double edge_sin = 0.34202014332566873;

/// 1 where the ray runs above the tilted plane through the eye, else 0.
inline float edge_value(const rt::ray_generator& gen, const rt::ray& r)
{
    const rt::vec3 p = r.origin + r.direction - gen.e;
    const double s = edge_cos * double(glm::dot(p, gen.basis.v)) - edge_sin * double(glm::dot(p, gen.basis.u));
    return s >= 0 ? 1.0f : 0.0f;
}

/// The fraction of pixel (i, j)'s square on the bright side of the edge.
inline double edge_coverage(const rt::ray_generator& gen, int i, int j)
{
    // the edge function at film position (x, y), by eq. 4.1: affine in x and y
    const rt::window& w = gen.plane;
    auto f = [&](double x, double y) {
        const double u = w.l + (double(w.r) - w.l) * x / gen.nx;
        const double v = w.b + (double(w.t) - w.b) * y / gen.ny;
        return edge_cos * v - edge_sin * u;
    };
    const double square[4][2] = {{double(i), double(j)}, {i + 1.0, double(j)}, {i + 1.0, j + 1.0}, {double(i), j + 1.0}};
    std::vector<double> xs, ys; // the clipped polygon
    for (int k = 0; k < 4; ++k) {
        const double* a = square[k];
        const double* b = square[(k + 1) % 4];
        const double fa = f(a[0], a[1]), fb = f(b[0], b[1]);
        if (fa >= 0) {
            xs.push_back(a[0]);
            ys.push_back(a[1]);
        }
        if ((fa >= 0) != (fb >= 0)) { // the side crosses the edge: add the crossing
            const double t = fa / (fa - fb);
            xs.push_back(a[0] + t * (b[0] - a[0]));
            ys.push_back(a[1] + t * (b[1] - a[1]));
        }
    }
    double twice_area = 0; // shoelace formula
    for (std::size_t k = 0; k < xs.size(); ++k) {
        const std::size_t next = (k + 1) % xs.size();
        twice_area += xs[k] * ys[next] - xs[next] * ys[k];
    }
    return std::fabs(twice_area) / 2; // the square's area is 1
}

struct edge_pictures {
    rt::image centre, sixteen;  ///< one ray through each pixel centre; 4 x 4 jittered samples, box
    int edge_pixels = 0;        ///< pixels the edge crosses (exact coverage strictly between 0 and 1)
    double rms_centre = 0, rms_one = 0, rms_sixteen = 0;  ///< over those pixels: centre, 1 and 16 jittered samples
};

/// The edge seen with the pixel centres, and with the student's jittered samples
/// (1 x 1 and 4 x 4) reconstructed by the student's box.
inline edge_pictures render_edge(const rt::ray_generator& gen)
{
    edge_pictures out;
    out.centre = rt::image(gen.nx, gen.ny);
    out.sixteen = rt::image(gen.nx, gen.ny);
    double sum_centre = 0, sum_one = 0, sum_sixteen = 0;
    for (int j = 0; j < gen.ny; ++j)
        for (int i = 0; i < gen.nx; ++i) {
            const std::uint64_t pixel_index = std::uint64_t(j) * std::uint64_t(gen.nx) + std::uint64_t(i);
            const float centre = edge_value(gen, rt::pixel_ray(gen, i, j));
            float estimate[2] = {0, 0};
            for (int k = 0; k < 2; ++k) {
                const int n = k == 0 ? 1 : 4;
                rt::pcg32 rng = rt::seeded_generator(edge_seed, pixel_index, std::uint64_t(n), edge_stream);
                const std::vector<rt::vec2> positions = rt::jittered_samples(i, j, n, rng);
                std::vector<rt::color> values;
                values.reserve(positions.size());
                for (const rt::vec2& p : positions)
                    values.emplace_back(edge_value(gen, rt::generate_ray(gen, p.x, p.y)));
                estimate[k] = rt::box_reconstruct(i, j, positions, values).r;
            }
            out.centre.at(i, gen.ny - 1 - j) = rt::color(centre);
            out.sixteen.at(i, gen.ny - 1 - j) = rt::color(estimate[1]);
            const double exact = edge_coverage(gen, i, j);
            if (exact > 0 && exact < 1) {
                ++out.edge_pixels;
                sum_centre += (centre - exact) * (centre - exact);
                sum_one += (estimate[0] - exact) * (estimate[0] - exact);
                sum_sixteen += (estimate[1] - exact) * (estimate[1] - exact);
            }
        }
    if (out.edge_pixels > 0) {
        out.rms_centre = std::sqrt(sum_centre / out.edge_pixels);
        out.rms_one = std::sqrt(sum_one / out.edge_pixels);
        out.rms_sixteen = std::sqrt(sum_sixteen / out.edge_pixels);
    }
    return out;
}

} // namespace stage
