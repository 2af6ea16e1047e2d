// All spheres of a scene tested eight at a time (AVX): the report's room is
// six huge spheres that nearly every ray meets, so this loop is hot.
#pragma once

#include <cstdint>
#include <vector>

#include <immintrin.h>

#include "geometry/ray.h"
#include "geometry/sphere.h"

namespace whisker {

class SphereSet {
 public:
  SphereSet() = default;
  // ids[k] is what intersect() reports for spheres[k] (default: k).
  explicit SphereSet(const std::vector<Sphere>& spheres, std::vector<std::uint32_t> ids = {});

  // Closest hit with t in (ray.tmin, tmax): writes t and the sphere index,
  // returns false if none. Same arithmetic as intersect_sphere().
  bool intersect(const Ray& ray, float tmax, float& t, std::uint32_t& index) const;
  // Whether a sphere blocks the ray in (tmin, tmax). `end_sphere` (an id, or
  // kNoSkip) is a sphere the segment ends on from outside, whose own side
  // the caller has checked (a point outside a sphere sees a point on it iff
  // it lies above that point's tangent plane): it is not tested, since near
  // the end float cannot tell the surface from a root a little before it.
  bool occluded(const Ray& ray, std::uint32_t end_sphere = kNoSkip) const;
  std::size_t size() const { return count_; }

  // Whether intersect_batch() serves this set: one to eight spheres.
  bool batchable() const { return count_ > 0 && count_ <= 8; }
  // intersect(*rays[l], rays[l]->tmax, t[l], index[l]) for each lane l
  // (bit l of `lanes`, l < 8), the rays side by side; returns the lanes that
  // hit. The same answers as intersect(), ray by ray.
  unsigned intersect_batch(const Ray* const* rays, unsigned lanes, float* t,
                           std::uint32_t* index) const;

 private:
  // One pass of intersect() / occluded(); see sphere_set.cpp.
  template <bool kExact>
  int intersect_pass(const Ray& r, float tmax, float& t, std::uint32_t& index) const;
  bool intersect_exact(const Ray& r, float tmax, float& t, std::uint32_t& index) const;
  template <bool kExact>
  int occluded_pass(const Ray& r, float end) const;
  bool occluded_exact(const Ray& r, float end) const;
  void redo_near(std::size_t k, unsigned near, const Ray& r, float tmax, float* t) const;
  int closest_of(std::size_t k, unsigned tie, const Ray& r, __m256 t) const;
  std::size_t count_ = 0;
  // Structure of arrays, padded to a multiple of 8 with spheres nothing hits.
  // idf_ holds the ids as floats (exact below 2^24), for the skip test;
  // near2_ is 2^-10 r^2, the near-surface bound.
  std::vector<float> cx_, cy_, cz_, r2_, near2_, idf_;
  std::vector<Sphere> spheres_;  // for the double-precision re-test
  std::vector<std::uint32_t> id_;
};

}  // namespace whisker
