#include "testing/pass_inspection.h"

#include <cmath>
#include <cstring>

namespace obscura {

void LsaoPassInspection::read_stats(const LsaoPass& pass, const gl::Table& gl, uint32_t out[3]) {
    uint32_t values[4] = {};
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, pass.stats_.name());
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof values, values);
    std::memcpy(out, values, 3 * sizeof(uint32_t));
}

void LsaoPassInspection::fill_values(const LsaoPass& pass, const gl::Table& gl, uint16_t half_bits) {
    const std::vector<uint16_t> halves(size_t(pass.layout().values), half_bits);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, pass.values_.name());
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(halves.size() * 2), halves.data());
}

std::vector<float> LsaoPassInspection::read_values(const LsaoPass& pass, const gl::Table& gl) {
    std::vector<uint16_t> halves(size_t(pass.layout().values));
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, pass.values_.name());
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(halves.size() * 2), halves.data());
    std::vector<float> out(halves.size());
    for (size_t i = 0; i < halves.size(); ++i) {
        // IEEE half -> float (values are finite: in [-1, 2] or OBSCURA_LSAO_NO_OCCLUDER).
        const uint32_t h = halves[i];
        const uint32_t sign = (h >> 15) & 1u, exponent = (h >> 10) & 31u, mantissa = h & 1023u;
        float magnitude = exponent == 0 ? std::ldexp(float(mantissa), -24)
                                        : std::ldexp(float(mantissa | 1024u), int(exponent) - 25);
        out[i] = sign ? -magnitude : magnitude;
    }
    return out;
}

std::vector<float> FfaoPassInspection::read_table(const FfaoPass& pass, const gl::Table& gl) {
    const size_t columns = size_t(OBSCURA_FFAO_TABLE_B) * OBSCURA_FFAO_TABLE_C * OBSCURA_FFAO_TABLE_D;
    std::vector<float> texels(size_t(OBSCURA_FFAO_TABLE_A) * columns);
    gl.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_FFAO_TABLE));
    gl.BindTexture(GL_TEXTURE_3D, pass.table_.name());
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.GetTexImage(GL_TEXTURE_3D, 0, GL_RED, GL_FLOAT, texels.data());
    gl.BindTexture(GL_TEXTURE_3D, 0);
    return texels;
}

std::vector<float> FfaoPassInspection::read_peaks(const FfaoPass& pass, const gl::Table& gl) {
    std::vector<float> values(size_t(pass.peaks_.bytes() / 4));
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, pass.peaks_.name());
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(values.size() * 4), values.data());
    return values;
}

}  // namespace obscura
