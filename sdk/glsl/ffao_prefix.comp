// FFAO's prefix-sum kernel (Timonen, HPG 2013, sec. 7): one invocation walks one interval column across its
// lines and replaces every entry with the sum of the entries before it and itself, in place, so the obscurance
// pass averages the peaks of any run of lines from two or three reads. The sums restart every 2^block_shift
// lines (sized on the CPU to the widest run a sector reaches at that level): a run then spans at most two
// blocks, and no sum grows beyond a block of nearby lines, which keeps float sums of depths exact enough next
// to far geometry in the same column.
#define OBSCURA_FFAO_PASS 1
#define OBSCURA_FFAO_CHUNK_PASS 1
#include "common/shader_interface.h"
#include "common/ffao.glsl"

layout(local_size_x = OBSCURA_FFAO_PREFIX_GROUP) in;

layout(std430, binding = OBSCURA_SSBO_FFAO_PEAKS) buffer FfaoPeaks { vec4 ffao_peaks[]; };

// Invocation x of layer j * levels + n of a chunk's dispatch: column x of level n of the chunk's j-th orientation.
void main() {
    int k = ffao_chunk.range.x + int(gl_GlobalInvocationID.z) / ffao_levels();  // one dispatch per chunk
    int n = int(gl_GlobalInvocationID.z) % ffao_levels();
    FfaoColumn column = ffao_column(k, n, int(gl_GlobalInvocationID.x));
    int block = 1 << column.block_shift;
    int first = column.offset - ffao_chunk.range.z;
    vec4 sum = vec4(0.0);
    for (int e = 0; e < column.lines; ++e) {
        if ((e & (block - 1)) == 0) sum = vec4(0.0);
        sum += ffao_peaks[first + e];
        ffao_peaks[first + e] = sum;
    }
}
