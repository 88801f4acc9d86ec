#include "gl_state_snapshot.h"

#include <sstream>

#include "gl_test_support.h"

namespace obscura_test {
namespace {

long long get_integer(GLenum pname) {
    GLint value = 0;
    glGetIntegerv(pname, &value);
    return value;
}

}  // namespace

Snapshot capture() {
    Snapshot s;
    s.add("CURRENT_PROGRAM", get_integer(GL_CURRENT_PROGRAM));
    s.add("TEXTURE_BUFFER (buffer binding)", get_integer(GL_TEXTURE_BUFFER));
    s.add("ACTIVE_TEXTURE", get_integer(GL_ACTIVE_TEXTURE));
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    const std::pair<GLenum, const char*> targets[] = {
        {GL_TEXTURE_BINDING_2D, "2D"},
        {GL_TEXTURE_BINDING_2D_MULTISAMPLE, "2D_MS"},
        {GL_TEXTURE_BINDING_3D, "3D"},
        {GL_TEXTURE_BINDING_CUBE_MAP, "CUBE"},
        {GL_TEXTURE_BINDING_2D_ARRAY, "2D_ARRAY"},
        {GL_TEXTURE_BINDING_BUFFER, "BUFFER"},
    };
    for (int unit = 0; unit < kSnapshotTextureUnits; ++unit) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        for (const auto& [pname, name] : targets)
            s.add("unit " + std::to_string(unit) + " TEXTURE_BINDING_" + name, get_integer(pname));
        s.add("unit " + std::to_string(unit) + " SAMPLER_BINDING", get_integer(GL_SAMPLER_BINDING));
    }
    glActiveTexture(GLenum(active));
    for (int unit = 0; unit < kSnapshotImageUnits; ++unit) {
        const std::pair<GLenum, const char*> image_params[] = {
            {GL_IMAGE_BINDING_NAME, "NAME"},     {GL_IMAGE_BINDING_LEVEL, "LEVEL"},
            {GL_IMAGE_BINDING_LAYERED, "LAYERED"}, {GL_IMAGE_BINDING_LAYER, "LAYER"},
            {GL_IMAGE_BINDING_ACCESS, "ACCESS"}, {GL_IMAGE_BINDING_FORMAT, "FORMAT"},
        };
        for (const auto& [pname, name] : image_params) {
            GLint value = 0;
            glGetIntegeri_v(pname, GLuint(unit), &value);
            s.add("image " + std::to_string(unit) + " " + name, value);
        }
    }
    const std::pair<GLenum, const char*> buffer_kinds[][4] = {
        {{GL_UNIFORM_BUFFER_BINDING, "UBO"}, {GL_UNIFORM_BUFFER_START, "UBO start"}, {GL_UNIFORM_BUFFER_SIZE, "UBO size"}},
        {{GL_SHADER_STORAGE_BUFFER_BINDING, "SSBO"}, {GL_SHADER_STORAGE_BUFFER_START, "SSBO start"},
         {GL_SHADER_STORAGE_BUFFER_SIZE, "SSBO size"}},
    };
    for (const auto& kind : buffer_kinds) {
        s.add(std::string("generic ") + kind[0].second, get_integer(kind[0].first));
        for (int index = 0; index < kSnapshotBufferIndices; ++index) {
            for (int k = 0; k < 3; ++k) {
                GLint64 value = 0;
                glGetInteger64i_v(kind[k].first, GLuint(index), &value);
                s.add(std::string(kind[k].second) + " [" + std::to_string(index) + "]", value);
            }
        }
    }
    s.add("ARRAY_BUFFER_BINDING", get_integer(GL_ARRAY_BUFFER_BINDING));
    s.add("PIXEL_PACK_BUFFER_BINDING", get_integer(GL_PIXEL_PACK_BUFFER_BINDING));
    s.add("PIXEL_UNPACK_BUFFER_BINDING", get_integer(GL_PIXEL_UNPACK_BUFFER_BINDING));
    s.add("DISPATCH_INDIRECT_BUFFER_BINDING", get_integer(GL_DISPATCH_INDIRECT_BUFFER_BINDING));
    s.add("COPY_READ_BUFFER_BINDING", get_integer(GL_COPY_READ_BUFFER_BINDING));
    s.add("VERTEX_ARRAY_BINDING", get_integer(GL_VERTEX_ARRAY_BINDING));
    s.add("RENDERBUFFER_BINDING", get_integer(GL_RENDERBUFFER_BINDING));
    s.add("READ_FRAMEBUFFER_BINDING", get_integer(GL_READ_FRAMEBUFFER_BINDING));
    s.add("DRAW_FRAMEBUFFER_BINDING", get_integer(GL_DRAW_FRAMEBUFFER_BINDING));
    s.add("READ_BUFFER", get_integer(GL_READ_BUFFER));
    GLint box[4];
    glGetIntegerv(GL_VIEWPORT, box);
    for (int i = 0; i < 4; ++i) s.add("VIEWPORT[" + std::to_string(i) + "]", box[i]);
    glGetIntegerv(GL_SCISSOR_BOX, box);
    for (int i = 0; i < 4; ++i) s.add("SCISSOR_BOX[" + std::to_string(i) + "]", box[i]);
    s.add("SCISSOR_TEST", glIsEnabled(GL_SCISSOR_TEST));
    s.add("BLEND", glIsEnabled(GL_BLEND));
    s.add("DEPTH_TEST", glIsEnabled(GL_DEPTH_TEST));
    s.add("RASTERIZER_DISCARD", glIsEnabled(GL_RASTERIZER_DISCARD));
    GLboolean mask[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, mask);
    for (int i = 0; i < 4; ++i) s.add("COLOR_WRITEMASK[" + std::to_string(i) + "]", mask[i]);
    s.add("PACK_ALIGNMENT", get_integer(GL_PACK_ALIGNMENT));
    s.add("PACK_ROW_LENGTH", get_integer(GL_PACK_ROW_LENGTH));
    s.add("PACK_SKIP_ROWS", get_integer(GL_PACK_SKIP_ROWS));
    s.add("UNPACK_ALIGNMENT", get_integer(GL_UNPACK_ALIGNMENT));
    s.add("UNPACK_ROW_LENGTH", get_integer(GL_UNPACK_ROW_LENGTH));
    s.add("UNPACK_SKIP_PIXELS", get_integer(GL_UNPACK_SKIP_PIXELS));
    return s;
}

std::string diff(const Snapshot& before, const Snapshot& after) {
    std::ostringstream out;
    for (size_t i = 0; i < before.values.size() && i < after.values.size(); ++i) {
        if (before.values[i].second != after.values[i].second)
            out << "  " << before.values[i].first << ": " << before.values[i].second << " -> " << after.values[i].second
                << "\n";
    }
    return out.str();
}

SentinelObjects::SentinelObjects(int textures_2d, int multisample_textures, int framebuffer_texture,
                                 ReadAttachment read) {
    const char* source = "#version 430 core\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
    program_ = HostProgram::create();
    GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    glAttachShader(program_.get(), shader);
    glLinkProgram(program_.get());
    glDeleteShader(shader);
    for (int i = 0; i < textures_2d; ++i) textures_2d_.push_back(make_texture(GL_RGBA8, 4, 4));
    for (int i = 0; i < multisample_textures; ++i) {
        HostTexture t = HostTexture::create();
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, t.get());
        glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, 2, GL_RGBA8, 4, 4, GL_TRUE);
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
        multisample_.push_back(std::move(t));
    }
    texture_3d_ = HostTexture::create();
    glBindTexture(GL_TEXTURE_3D, texture_3d_.get());
    glTexStorage3D(GL_TEXTURE_3D, 1, GL_RGBA16F, 4, 4, 4);
    glBindTexture(GL_TEXTURE_3D, 0);
    texture_array_ = HostTexture::create();
    glBindTexture(GL_TEXTURE_2D_ARRAY, texture_array_.get());
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 2, GL_RGBA8, 8, 8, 4);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    texture_cube_ = HostTexture::create();
    glBindTexture(GL_TEXTURE_CUBE_MAP, texture_cube_.get());
    glTexStorage2D(GL_TEXTURE_CUBE_MAP, 1, GL_RGBA8, 4, 4);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    image_r32f_ = make_texture(GL_R32F, 4, 4);
    for (int i = 0; i < kBuffers; ++i) {
        HostBuffer b = HostBuffer::create();
        glBindBuffer(GL_COPY_WRITE_BUFFER, b.get());
        glBufferData(GL_COPY_WRITE_BUFFER, 4096, nullptr, GL_STATIC_DRAW);
        buffers_.push_back(std::move(b));
    }
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    texture_buffer_ = HostTexture::create();
    glBindTexture(GL_TEXTURE_BUFFER, texture_buffer_.get());
    glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, buffers_[0].get());
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    glGenSamplers(kSamplers, samplers_);
    vertex_array_ = HostVertexArray::create();
    for (int i = 0; i < kFramebuffers; ++i) {
        HostFramebuffer f = HostFramebuffer::create();
        glBindFramebuffer(GL_FRAMEBUFFER, f.get());
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                               texture_2d(framebuffer_texture + i), 0);
        if (read == ReadAttachment::One) {
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D,
                                   texture_2d(framebuffer_texture + kFramebuffers), 0);
            if (i == 0) glReadBuffer(GL_COLOR_ATTACHMENT1);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        framebuffers_.push_back(std::move(f));
    }
    renderbuffer_ = HostRenderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer_.get());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 4, 4);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
}

// Samplers have no owner type of their own in host_gl_objects.h; everything else deletes itself.
SentinelObjects::~SentinelObjects() { glDeleteSamplers(kSamplers, samplers_); }

void set_sentinel_pixel_store() {
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, 13);
    glPixelStorei(GL_PACK_SKIP_ROWS, 3);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 17);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 5);
}

void set_default_pixel_store() {
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_PACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
}

}  // namespace obscura_test
