// Shared by FFAO's scan, prefix-sum and obscurance passes: the scan grid of a line orientation and the
// records of its lines and interval columns (FfaoLayout, passes/ffao_layout.h). Needs FfaoConstants.
//
// Orientation k scans lines one texel apart along dir_k. In the grid's (u, v) coordinates (along and across
// dir_k, relative to the grid origin) step j of line l sits at u = j + 0.5, v = l + 0.5. The level-n interval
// i of a line is its steps [i B_n, (i + 1) B_n), B_n = B0 2^n, so intervals of all lines line up across the
// orientation; column (k, n, i) holds the entries of lines first_line ... first_line + lines - 1 in order.

struct FfaoColumn {
    int offset;      // index of the first line's entry in the peaks buffer
    int first_line;  // l of the first line with a step in the interval
    int lines;       // lines with a step in it (0: none)
    int block_shift; // prefix sums restart every 2^block_shift entries
};

// A program that defines OBSCURA_FFAO_BUFFER_TEXTURES 1 (the obscurance pass on CPU rasterisers) reads the
// records and peaks as buffer textures: those rasterisers fetch texels with vector gathers but load storage
// buffers one invocation at a time. GPUs read them as storage buffers, through their caches.
#if defined(OBSCURA_FFAO_BUFFER_TEXTURES) && OBSCURA_FFAO_BUFFER_TEXTURES
layout(binding = OBSCURA_UNIT_FFAO_COLUMNS) uniform usamplerBuffer u_ffao_columns;
uvec4 ffao_column_record(int index) { return texelFetch(u_ffao_columns, index); }
#else
layout(std430, binding = OBSCURA_SSBO_FFAO_COLUMNS) readonly buffer FfaoColumns { uvec4 ffao_columns[]; };
uvec4 ffao_column_record(int index) { return ffao_columns[index]; }
#endif

int ffao_levels() { return ffao.config.w; }
int ffao_base_interval() { return ffao.config.z; }

int ffao_column_count(int k, int n) {
    int i = k * OBSCURA_FFAO_MAX_LEVELS + n;
    return ffao.column_count[i >> 2][i & 3];
}

// Column i of level n of orientation k; lines = 0 outside the grid.
FfaoColumn ffao_column(int k, int n, int i) {
    FfaoColumn column = FfaoColumn(0, 0, 0, 0);
    if (i < 0 || i >= ffao_column_count(k, n)) return column;
    int index = k * OBSCURA_FFAO_MAX_LEVELS + n;
    uvec4 record = ffao_column_record(ffao.column_base[index >> 2][index & 3] + i);
    column.offset = int(record.x);
    column.first_line = int(record.y);
    column.lines = int(record.z);
    column.block_shift = int(record.w);
    return column;
}
