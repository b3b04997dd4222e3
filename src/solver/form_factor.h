// Point-to-polygon form factors: the exact unoccluded one and the EQ 7 sample kernel.
#pragma once

#include <numbers>

#include "core/math.h"

namespace rad {

/// Unoccluded form factor from a differential area at `x` with unit normal `n` to the triangle
/// (a, b, c), by Lambert's contour integral (Baum, Rushmeier, Winget, SIGGRAPH 1989):
///   F = 1/(2 pi) * sum_i angle(R_i, R_i+1) * n . unit(R_i x R_i+1),  R_i = p_i - x.
/// The triangle is first clipped to the half-space in front of x, so parts behind the tangent
/// plane count for nothing and parts in front count fully. One-sidedness of the source is the
/// caller's business. Result in [0, 1].
///
/// Arithmetic of the contour sum: its edge terms are ~edge/distance each while their sum is
/// ~(edge/distance)^2, so rounding costs a relative error of about epsilon * distance / edge.
/// Single is enough (and about twice as fast) within a few dozen edge lengths of the source;
/// farther off use Double.
enum class Arithmetic { Single, Double };
float point_to_triangle_form_factor(const Vec3& x, const Vec3& n, const Vec3& a, const Vec3& b,
                                    const Vec3& c, Arithmetic arithmetic = Arithmetic::Double);

/// Unoccluded form factor from a differential area at `x` with unit normal `n` to a surface
/// bounded by the directed edges a[i] -> b[i] (in any order: contour integrals add up), which x
/// must see from the front everywhere (receiver_side == +1 in gather.h). The surface is clipped to
/// the half-space in front of x: each edge is cut where it crosses the tangent plane, and the part
/// of the clipped boundary that runs in the tangent plane, whose contour term is only its
/// change of polar angle about n, is the sum over crossings of +-(polar angle), entering minus
/// leaving, so no loops need building. `axis` is the surface's mean normal: the polar angles
/// are measured from the foot of x on the line where the two planes meet, which keeps them on
/// one branch. Result in [0, 1].
float point_to_outline_form_factor(const Vec3& x, const Vec3& n, const Vec3* a, const Vec3* b,
                                   size_t count, const Vec3& axis,
                                   Arithmetic arithmetic = Arithmetic::Double);

/// The EQ 7 weight of one source sample (Wallace, Elmquist, Haines, SIGGRAPH 1989):
///   cos(theta_r) cos(theta_s) / (pi r^2 + A/n),
/// 0 when the sample is behind the receiver or the receiver behind the sample's source.
/// `d` = sample - receiver; `n_r`, `n_s` unit normals; `area_per_sample` = A/n.
inline float sample_kernel(const Vec3& d, const Vec3& n_r, const Vec3& n_s, float area_per_sample) {
  const float r2 = glm::dot(d, d);
  const float cr = glm::dot(n_r, d), cs = -glm::dot(n_s, d);
  if (cr <= 0.0f || cs <= 0.0f || r2 <= 0.0f) return 0.0f;
  return cr * cs / (r2 * (std::numbers::pi_v<float> * r2 + area_per_sample));
}

}  // namespace rad
