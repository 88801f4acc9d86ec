// The host's GL state as the SDK promises to leave it: every binding and setting that the state-preservation tests
// set to sentinels, captured as named integers, and the difference of two captures; and the host objects those
// sentinels bind. Shared by the tests that check the state contract (state_preservation_test.cpp, soak_test.cpp)
// and those that check it on failure paths (allocation_failure_test.cpp).
#ifndef OBSCURA_TESTS_GL_STATE_SNAPSHOT_H
#define OBSCURA_TESTS_GL_STATE_SNAPSHOT_H

#include <string>
#include <utility>
#include <vector>

#include "gl_test_support.h"

namespace obscura_test {

// How much of each indexed state a snapshot covers.
constexpr int kSnapshotTextureUnits = 8;
constexpr int kSnapshotSamplerUnits = 4;
constexpr int kSnapshotImageUnits = 7;  // the SDK uses 6 (the z pyramid writes six levels) and one beyond
constexpr int kSnapshotBufferIndices = 3;

// Every piece of state the sentinel setup touches, as plain integers, with names for the diff.
struct Snapshot {
    std::vector<std::pair<std::string, long long>> values;
    void add(const std::string& name, long long value) { values.emplace_back(name, value); }
};

// The current context's state.
Snapshot capture();

// Names of the entries that differ, with both values; empty when none does.
std::string diff(const Snapshot& before, const Snapshot& after);

// The pixel-store state of the sentinel setups (pack and unpack alignment, row length and skips, none of them GL's
// default), and GL's defaults for it.
void set_sentinel_pixel_store();
void set_default_pixel_store();

// The host's objects that sentinel state binds, of every kind a snapshot's bindings name: a program (an empty
// compute shader), 4x4 RGBA8 2D and multisample textures, a 3D, an array, a cube-map, an R32F (for an image unit)
// and a buffer texture (on buffer(0)), 4 KiB buffers, samplers, a vertex array, two framebuffers and a
// renderbuffer; all deleted with it. Where each is bound is the test's choice: the soak binds them uniformly on every
// unit a snapshot covers, StatePreservation puts particular ones where given passes bind.
class SentinelObjects {
public:
    static constexpr int kBuffers = 5;
    static constexpr int kSamplers = 5;
    static constexpr int kFramebuffers = 2;

    // What framebuffer(0), the one to bind for reading, reads: its colour attachment 0 (GL's default), or attachment 1
    // (a read buffer other than the default, for the SDK to leave as it found it).
    enum class ReadAttachment { Zero, One };

    // Framebuffer i draws into texture_2d(framebuffer_texture + i); with ReadAttachment::One both also draw into
    // texture_2d(framebuffer_texture + 2) as colour attachment 1.
    SentinelObjects(int textures_2d, int multisample_textures, int framebuffer_texture, ReadAttachment read);
    ~SentinelObjects();
    SentinelObjects(const SentinelObjects&) = delete;
    SentinelObjects& operator=(const SentinelObjects&) = delete;

    GLuint program() const { return program_.get(); }
    GLuint texture_2d(int i) const { return textures_2d_[size_t(i)].get(); }
    GLuint multisample(int i) const { return multisample_[size_t(i)].get(); }
    GLuint texture_3d() const { return texture_3d_.get(); }
    GLuint texture_array() const { return texture_array_.get(); }
    GLuint texture_cube() const { return texture_cube_.get(); }
    GLuint image_r32f() const { return image_r32f_.get(); }
    GLuint texture_buffer() const { return texture_buffer_.get(); }
    GLuint buffer(int i) const { return buffers_[size_t(i)].get(); }
    GLuint sampler(int i) const { return samplers_[i]; }
    GLuint vertex_array() const { return vertex_array_.get(); }
    GLuint framebuffer(int i) const { return framebuffers_[size_t(i)].get(); }
    GLuint renderbuffer() const { return renderbuffer_.get(); }

private:
    HostProgram program_;
    std::vector<HostTexture> textures_2d_, multisample_;
    HostTexture texture_3d_, texture_array_, texture_cube_, image_r32f_, texture_buffer_;
    std::vector<HostBuffer> buffers_;
    GLuint samplers_[kSamplers] = {};
    HostVertexArray vertex_array_;
    std::vector<HostFramebuffer> framebuffers_;
    HostRenderbuffer renderbuffer_;
};

}  // namespace obscura_test

#endif  // OBSCURA_TESTS_GL_STATE_SNAPSHOT_H
