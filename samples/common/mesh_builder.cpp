#include "mesh_builder.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace obscura::samples {
namespace {

constexpr float kTwoPi = 2.0f * glm::pi<float>();

// e1, e2 perpendicular to the unit vector `axis` with cross(e1, e2) == axis.
void perpendicular_basis(const glm::vec3& axis, glm::vec3& e1, glm::vec3& e2) {
    const glm::vec3 helper = std::fabs(axis.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    e1 = glm::normalize(glm::cross(helper, axis));
    e2 = glm::cross(axis, e1);
}

// A box given by its centre, half sizes and a rotation (columns: the box's axes in the world).
void oriented_box(MeshBuilder& builder, const glm::vec3& centre, const glm::vec3& half, const glm::mat3& rotation,
                  unsigned faces) {
    for (int axis = 0; axis < 3; ++axis) {
        for (int side_index = 0; side_index < 2; ++side_index) {
            if (!(faces & (1u << (axis * 2 + side_index)))) continue;
            const float side = side_index == 0 ? -1.0f : 1.0f;
            // Face `axis` on `side`, spanned by the two other axes; (u, v, normal) is right-handed for
            // side +1, so the corner order is reversed for side -1.
            glm::vec3 normal(0.0f), u(0.0f), v(0.0f);
            normal[axis] = side;
            u[(axis + 1) % 3] = half[(axis + 1) % 3];
            v[(axis + 2) % 3] = half[(axis + 2) % 3];
            const glm::vec3 face = normal * half[axis];
            auto corner = [&](float su, float sv) { return centre + rotation * (face + su * u + sv * v); };
            if (side > 0.0f) {
                builder.quad(corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1), rotation * normal);
            } else {
                builder.quad(corner(-1, -1), corner(-1, 1), corner(1, 1), corner(1, -1), rotation * normal);
            }
        }
    }
}

}  // namespace

void MeshBuilder::set_placement(const glm::vec3& offset, float yaw_degrees) {
    placement_ = glm::rotate(glm::translate(glm::mat4(1.0f), offset), glm::radians(yaw_degrees),
                             glm::vec3(0.0f, 1.0f, 0.0f));
}

void MeshBuilder::vertex(const glm::vec3& position, const glm::vec3& normal) {
    const glm::vec3 p = glm::vec3(placement_ * glm::vec4(position, 1.0f));
    const glm::vec3 n = glm::normalize(glm::mat3(placement_) * normal);
    mesh_.vertices.insert(mesh_.vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
}

void MeshBuilder::triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& normal) {
    vertex(a, normal);
    vertex(b, normal);
    vertex(c, normal);
}

void MeshBuilder::triangle(const glm::vec3& a, const glm::vec3& na, const glm::vec3& b, const glm::vec3& nb,
                           const glm::vec3& c, const glm::vec3& nc) {
    vertex(a, na);
    vertex(b, nb);
    vertex(c, nc);
}

void MeshBuilder::quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                       const glm::vec3& normal) {
    triangle(a, b, c, normal);
    triangle(a, c, d, normal);
}

void MeshBuilder::quad_grid(const glm::vec3& corner, const glm::vec3& edge_u, const glm::vec3& edge_v, int nu,
                            int nv) {
    const glm::vec3 normal = glm::normalize(glm::cross(edge_u, edge_v));
    auto point = [&](int i, int j) {
        return corner + edge_u * (float(i) / float(nu)) + edge_v * (float(j) / float(nv));
    };
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) quad(point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1), normal);
    }
}

void MeshBuilder::box(const glm::vec3& lo, const glm::vec3& hi, unsigned faces) {
    oriented_box(*this, 0.5f * (lo + hi), 0.5f * (hi - lo), glm::mat3(1.0f), faces);
}

void MeshBuilder::box(const glm::vec3& base, const glm::vec3& size, float yaw_degrees, unsigned faces) {
    const float yaw = glm::radians(yaw_degrees);
    const glm::mat3 rotation(glm::vec3(std::cos(yaw), 0.0f, -std::sin(yaw)), glm::vec3(0.0f, 1.0f, 0.0f),
                             glm::vec3(std::sin(yaw), 0.0f, std::cos(yaw)));
    const glm::vec3 half = size * 0.5f;
    oriented_box(*this, base + glm::vec3(0.0f, half.y, 0.0f), half, rotation, faces);
}

void MeshBuilder::cylinder(const glm::vec3& base, float radius, float height, int segments, unsigned caps) {
    cylinder_between(base, base + glm::vec3(0.0f, height, 0.0f), radius, segments, caps);
}

void MeshBuilder::cylinder_between(const glm::vec3& a, const glm::vec3& b, float radius, int segments,
                                   unsigned caps) {
    const glm::vec3 axis = glm::normalize(b - a);
    glm::vec3 e1, e2;
    perpendicular_basis(axis, e1, e2);
    auto radial = [&](int i) {
        const float phi = kTwoPi * float(i) / float(segments);
        return std::cos(phi) * e1 + std::sin(phi) * e2;
    };
    for (int i = 0; i < segments; ++i) {
        const glm::vec3 r0 = radial(i), r1 = radial(i + 1);
        // Counter-clockwise seen from outside: around the axis, then up.
        triangle(a + radius * r0, r0, a + radius * r1, r1, b + radius * r1, r1);
        triangle(a + radius * r0, r0, b + radius * r1, r1, b + radius * r0, r0);
        if (caps & kCapTop) triangle(b, b + radius * r0, b + radius * r1, axis);
        if (caps & kCapBottom) triangle(a, a + radius * r1, a + radius * r0, -axis);
    }
}

void MeshBuilder::sphere(const glm::vec3& centre, float radius, int slices, int stacks) {
    auto direction = [&](int slice, int stack) {
        const float theta = glm::pi<float>() * float(stack) / float(stacks);  // from +y down
        const float phi = kTwoPi * float(slice) / float(slices);
        return glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    };
    for (int stack = 0; stack < stacks; ++stack) {
        for (int slice = 0; slice < slices; ++slice) {
            // Increasing phi then increasing theta is counter-clockwise seen from outside.
            const glm::vec3 a = direction(slice, stack), b = direction(slice + 1, stack);
            const glm::vec3 c = direction(slice + 1, stack + 1), d = direction(slice, stack + 1);
            if (stack > 0) triangle(centre + radius * a, a, centre + radius * b, b, centre + radius * c, c);
            if (stack < stacks - 1) triangle(centre + radius * a, a, centre + radius * c, c, centre + radius * d, d);
        }
    }
}

void MeshBuilder::torus(const glm::vec3& centre, const glm::vec3& axis_in, float major, float minor, int segments,
                        int sides) {
    const glm::vec3 axis = glm::normalize(axis_in);
    glm::vec3 e1, e2;
    perpendicular_basis(axis, e1, e2);
    auto normal_at = [&](int i, int j) {
        const float u = kTwoPi * float(i) / float(segments), v = kTwoPi * float(j) / float(sides);
        const glm::vec3 radial = std::cos(u) * e1 + std::sin(u) * e2;
        return std::cos(v) * radial + std::sin(v) * axis;
    };
    auto point_at = [&](int i, int j) {
        const float u = kTwoPi * float(i) / float(segments);
        const glm::vec3 radial = std::cos(u) * e1 + std::sin(u) * e2;
        return centre + major * radial + minor * normal_at(i, j);
    };
    for (int i = 0; i < segments; ++i) {
        for (int j = 0; j < sides; ++j) {
            // dP/du x dP/dv points away from the tube's centre line.
            const glm::vec3 pa = point_at(i, j), pb = point_at(i + 1, j), pc = point_at(i + 1, j + 1),
                            pd = point_at(i, j + 1);
            const glm::vec3 na = normal_at(i, j), nb = normal_at(i + 1, j), nc = normal_at(i + 1, j + 1),
                            nd = normal_at(i, j + 1);
            triangle(pa, na, pb, nb, pc, nc);
            triangle(pa, na, pc, nc, pd, nd);
        }
    }
}

void MeshBuilder::arch(const ArchShape& shape) {
    // Local frame: u along the span, v up, w = u x v (so (u, v, w) is right-handed).
    const glm::vec3 u_axis = glm::normalize(shape.along);
    const glm::vec3 v_axis(0.0f, 1.0f, 0.0f);
    const glm::vec3 w_axis = glm::cross(u_axis, v_axis);
    const float h = shape.half_span, r = shape.radius, top = shape.height, t = 0.5f * shape.thickness;
    auto at = [&](float u, float v, float w) { return shape.springing + u * u_axis + v * v_axis + w * w_axis; };

    // Angles of the half circle, plus the two directions through the block's top corners, so that
    // every front-face quad (arc point, outer point, next outer point, next arc point) is flat on
    // one side of the outline.
    std::vector<float> angles;
    for (int i = 0; i <= shape.segments; ++i) angles.push_back(glm::pi<float>() * float(i) / float(shape.segments));
    const float corner = std::atan2(top, h);
    angles.push_back(corner);
    angles.push_back(glm::pi<float>() - corner);
    std::sort(angles.begin(), angles.end());
    angles.erase(std::unique(angles.begin(), angles.end(), [](float x, float y) { return std::fabs(x - y) < 1e-6f; }),
                 angles.end());

    auto outer = [&](float angle) {
        const float c = std::cos(angle), s = std::sin(angle);
        float distance = std::fabs(c) > 1e-6f ? h / std::fabs(c) : 1e30f;
        if (s > 1e-6f) distance = std::min(distance, top / s);
        return glm::vec2(c * distance, s * distance);
    };
    for (size_t k = 0; k + 1 < angles.size(); ++k) {
        const float a0 = angles[k], a1 = angles[k + 1];
        const glm::vec2 arc0(r * std::cos(a0), r * std::sin(a0)), arc1(r * std::cos(a1), r * std::sin(a1));
        const glm::vec2 out0 = outer(a0), out1 = outer(a1);
        // Front (+w) and back (-w) faces.
        quad(at(arc0.x, arc0.y, t), at(out0.x, out0.y, t), at(out1.x, out1.y, t), at(arc1.x, arc1.y, t), w_axis);
        quad(at(arc1.x, arc1.y, -t), at(out1.x, out1.y, -t), at(out0.x, out0.y, -t), at(arc0.x, arc0.y, -t), -w_axis);
        // Intrados: the curved underside, normals towards the centre of the opening.
        const glm::vec3 n0 = -(std::cos(a0) * u_axis + std::sin(a0) * v_axis);
        const glm::vec3 n1 = -(std::cos(a1) * u_axis + std::sin(a1) * v_axis);
        const glm::vec3 f0 = at(arc0.x, arc0.y, t), f1 = at(arc1.x, arc1.y, t);
        const glm::vec3 b0 = at(arc0.x, arc0.y, -t), b1 = at(arc1.x, arc1.y, -t);
        triangle(f0, n0, f1, n1, b1, n1);
        triangle(f0, n0, b1, n1, b0, n0);
    }
    quad(at(-h, top, t), at(h, top, t), at(h, top, -t), at(-h, top, -t), v_axis);
    if (shape.end_faces) {
        quad(at(h, 0, t), at(h, 0, -t), at(h, top, -t), at(h, top, t), u_axis);
        quad(at(-h, 0, -t), at(-h, 0, t), at(-h, top, t), at(-h, top, -t), -u_axis);
    }
    if (h - r > 1e-6f) {
        quad(at(r, 0, -t), at(h, 0, -t), at(h, 0, t), at(r, 0, t), -v_axis);
        quad(at(-h, 0, -t), at(-r, 0, -t), at(-r, 0, t), at(-h, 0, t), -v_axis);
    }
}

void MeshBuilder::stairs(const glm::vec3& foot, const glm::vec3& climb, float width, int steps, float rise,
                         float run) {
    const glm::vec3 u_axis = glm::normalize(climb);
    const glm::vec3 v_axis(0.0f, 1.0f, 0.0f);
    const glm::vec3 w_axis = glm::cross(u_axis, v_axis);
    const float hw = 0.5f * width;
    auto at = [&](float u, float v, float w) { return foot + u * u_axis + v * v_axis + w * w_axis; };
    for (int k = 0; k < steps; ++k) {
        const float u0 = float(k) * run, u1 = float(k + 1) * run;
        const float y0 = float(k) * rise, y1 = float(k + 1) * rise;
        quad(at(u0, y0, -hw), at(u0, y0, hw), at(u0, y1, hw), at(u0, y1, -hw), -u_axis);  // riser
        quad(at(u0, y1, -hw), at(u0, y1, hw), at(u1, y1, hw), at(u1, y1, -hw), v_axis);   // tread
        quad(at(u0, 0, hw), at(u1, 0, hw), at(u1, y1, hw), at(u0, y1, hw), w_axis);       // sides
        quad(at(u0, 0, -hw), at(u0, y1, -hw), at(u1, y1, -hw), at(u1, 0, -hw), -w_axis);
    }
    const float length = float(steps) * run, height = float(steps) * rise;
    quad(at(length, 0, -hw), at(length, height, -hw), at(length, height, hw), at(length, 0, hw), u_axis);
}

namespace {

struct SurfaceGrid {
    int nu = 0, nv = 0;
    std::vector<glm::vec3> positions, normals;  // (nu + 1) x (nv + 1), s fastest
    const glm::vec3& p(int i, int j) const { return positions[size_t(j) * size_t(nu + 1) + size_t(i)]; }
    const glm::vec3& n(int i, int j) const { return normals[size_t(j) * size_t(nu + 1) + size_t(i)]; }
};

SurfaceGrid sample_surface(int nu, int nv, const MeshBuilder::SurfaceFunction& position) {
    SurfaceGrid grid;
    grid.nu = nu;
    grid.nv = nv;
    constexpr float kStep = 1e-3f;
    for (int j = 0; j <= nv; ++j) {
        for (int i = 0; i <= nu; ++i) {
            const float s = float(i) / float(nu), t = float(j) / float(nv);
            const float s0 = std::max(0.0f, s - kStep), s1 = std::min(1.0f, s + kStep);
            const float t0 = std::max(0.0f, t - kStep), t1 = std::min(1.0f, t + kStep);
            const glm::vec3 ds = (position(s1, t) - position(s0, t)) / (s1 - s0);
            const glm::vec3 dt = (position(s, t1) - position(s, t0)) / (t1 - t0);
            grid.positions.push_back(position(s, t));
            grid.normals.push_back(glm::normalize(glm::cross(ds, dt)));
        }
    }
    return grid;
}

}  // namespace

void MeshBuilder::surface(int nu, int nv, const SurfaceFunction& position) {
    const SurfaceGrid g = sample_surface(nu, nv, position);
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            triangle(g.p(i, j), g.n(i, j), g.p(i + 1, j), g.n(i + 1, j), g.p(i + 1, j + 1), g.n(i + 1, j + 1));
            triangle(g.p(i, j), g.n(i, j), g.p(i + 1, j + 1), g.n(i + 1, j + 1), g.p(i, j + 1), g.n(i, j + 1));
        }
    }
}

void MeshBuilder::thick_surface(int nu, int nv, const SurfaceFunction& position, float thickness) {
    const SurfaceGrid g = sample_surface(nu, nv, position);
    const float half = 0.5f * thickness;
    auto front = [&](int i, int j) { return g.p(i, j) + half * g.n(i, j); };
    auto back = [&](int i, int j) { return g.p(i, j) - half * g.n(i, j); };
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            triangle(front(i, j), g.n(i, j), front(i + 1, j), g.n(i + 1, j), front(i + 1, j + 1), g.n(i + 1, j + 1));
            triangle(front(i, j), g.n(i, j), front(i + 1, j + 1), g.n(i + 1, j + 1), front(i, j + 1), g.n(i, j + 1));
            triangle(back(i, j), -g.n(i, j), back(i + 1, j + 1), -g.n(i + 1, j + 1), back(i + 1, j), -g.n(i + 1, j));
            triangle(back(i, j), -g.n(i, j), back(i, j + 1), -g.n(i, j + 1), back(i + 1, j + 1), -g.n(i + 1, j + 1));
        }
    }
    // The rim: flat strips whose corner order makes them face away from the sheet.
    auto rim = [&](const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d) {
        const glm::vec3 cross = glm::cross(b - a, c - a);
        if (glm::dot(cross, cross) > 0.0f) quad(a, b, c, d, glm::normalize(cross));
    };
    for (int j = 0; j < nv; ++j) {
        rim(front(0, j), front(0, j + 1), back(0, j + 1), back(0, j));
        rim(front(nu, j), back(nu, j), back(nu, j + 1), front(nu, j + 1));
    }
    for (int i = 0; i < nu; ++i) {
        rim(front(i, 0), back(i, 0), back(i + 1, 0), front(i + 1, 0));
        rim(front(i, nv), front(i + 1, nv), back(i + 1, nv), back(i, nv));
    }
}

}  // namespace obscura::samples
