// embree_scene.hpp - one rt::mesh in an Embree 3 scene, for the benchmarks
// that compare rt with Embree (embree.cpp: rays; frame.cpp: whole frames).
// Not part of rt: only the benchmark programs link Embree.
//
//     bench::embree_scene e(mesh, "threads=1", RTC_BUILD_QUALITY_HIGH);
//     float t = e.closest(ray, 0, tmax);   // infinity on a miss
#pragma once

#include <embree3/rtcore.h>

#include <limits>
#include <string>

#include <rt/core/error.hpp>
#include <rt/scene/mesh.hpp>
#include <rt/core/ray.hpp>

#include "bench.hpp"

namespace bench {

class embree_scene {
public:
    /// `quality`: Embree's default (medium) builds a binned SAH tree without
    /// spatial splits; high builds with them (its "fast spatial" builder).
    embree_scene(const rt::mesh& m, const char* config, RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM)
    {
        device_ = rtcNewDevice(config);
        if (!device_)
            throw rt::error("bench: rtcNewDevice failed (error " +
                            std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
        const auto start = bench::clock::now();
        scene_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene_, quality);
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.positions.size()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m.triangles.size()));
        if (!vertices || !indices)
            throw rt::error("bench: Embree could not allocate the mesh's buffers");
        for (std::size_t k = 0; k < m.positions.size(); ++k)
            for (int axis = 0; axis < 3; ++axis)
                vertices[3 * k + std::size_t(axis)] = float(m.positions[k][axis]);
        for (std::size_t k = 0; k < m.triangles.size(); ++k)
            for (std::size_t corner = 0; corner < 3; ++corner)
                indices[3 * k + corner] = m.triangles[k][corner];
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene_, geometry);
        rtcReleaseGeometry(geometry);
        rtcCommitScene(scene_);
        build_seconds_ = bench::seconds_since(start);
        if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
            throw rt::error("bench: Embree failed to build the scene");
    }
    embree_scene(const embree_scene&) = delete;
    embree_scene& operator=(const embree_scene&) = delete;
    ~embree_scene()
    {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }

    double build_seconds() const { return build_seconds_; }

    static constexpr float infinity = std::numeric_limits<float>::infinity();

    float closest(const rt::ray& r, float tmin, float tmax) const
    {
        const RTCRayHit query = intersect(r, tmin, tmax);
        return query.hit.geomID == RTC_INVALID_GEOMETRY_ID ? infinity : query.ray.tfar;
    }

    /// The closest hit's t, triangle and geometric normal (unit, not oriented).
    bool closest_with_normal(const rt::ray& r, float tmax, float& t, unsigned& triangle, rt::vec3& normal,
                             float tmin = 0) const
    {
        float u = 0, v = 0;
        return closest_with_normal(r, tmax, t, triangle, normal, u, v, tmin);
    }

    /// The same, with Embree's barycentrics: the hit is (1 - u - v) v0 + u v1 + v v2.
    bool closest_with_normal(const rt::ray& r, float tmax, float& t, unsigned& triangle, rt::vec3& normal, float& u,
                             float& v, float tmin = 0) const
    {
        const RTCRayHit query = intersect(r, tmin, tmax);
        if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID)
            return false;
        t = query.ray.tfar;
        triangle = query.hit.primID;
        normal = glm::normalize(rt::vec3(rt::real(query.hit.Ng_x), rt::real(query.hit.Ng_y), rt::real(query.hit.Ng_z)));
        u = query.hit.u;
        v = query.hit.v;
        return true;
    }

    bool occluded(const rt::ray& r, float tmin, float tmax) const
    {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRay query;
        set_ray(query, r, tmax, tmin);
        rtcOccluded1(scene_, &context, &query);
        return query.tfar < 0; // Embree sets tfar = -inf on a hit
    }

private:
    /// rtcIntersect1 of one ray: the hit's geomID is RTC_INVALID_GEOMETRY_ID on a miss.
    RTCRayHit intersect(const rt::ray& r, float tmin, float tmax) const
    {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit query;
        set_ray(query.ray, r, tmax, tmin);
        query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &context, &query);
        return query;
    }

    static void set_ray(RTCRay& out, const rt::ray& r, float tmax, float tmin = 0)
    {
        out.org_x = float(r.origin.x);
        out.org_y = float(r.origin.y);
        out.org_z = float(r.origin.z);
        out.dir_x = float(r.direction.x);
        out.dir_y = float(r.direction.y);
        out.dir_z = float(r.direction.z);
        out.tnear = tmin;
        out.tfar = tmax;
        out.time = 0;
        out.mask = ~0u;
        out.id = 0;
        out.flags = 0;
    }

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    double build_seconds_ = 0;
};

} // namespace bench
