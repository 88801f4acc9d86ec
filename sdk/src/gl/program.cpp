#include "gl/program.h"

#include <cstring>

#include "gl/shader_sources.h"

namespace obscura::gl {
namespace {

constexpr int kMaxIncludeDepth = 8;

int find_shader(const char* path, size_t length) {
    for (size_t i = 0; i < kEmbeddedShaderCount; ++i) {
        if (std::strlen(kEmbeddedShaders[i].path) == length &&
            std::strncmp(kEmbeddedShaders[i].path, path, length) == 0) {
            return int(i);
        }
    }
    return -1;
}

// Appends shader `index` to `out`, expanding includes. Each file appears once (include guards are
// implicit); #line <line> <file index> keeps driver messages pointing at the original file.
Error expand(int index, int depth, HostVector<char>* included, HostString* out) {
    if (depth > kMaxIncludeDepth) {
        return Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "shader include depth exceeds %d at %s", kMaxIncludeDepth,
                           kEmbeddedShaders[index].path);
    }
    (*included)[size_t(index)] = 1;
    const EmbeddedShader& file = kEmbeddedShaders[index];
    const char* cursor = file.source;
    const char* end = file.source + file.length;
    int line = 1;
    char marker[64];
    std::snprintf(marker, sizeof marker, "#line 1 %d\n", index);
    out->append(marker);
    while (cursor < end) {
        const char* eol = static_cast<const char*>(std::memchr(cursor, '\n', size_t(end - cursor)));
        const char* line_end = eol ? eol : end;
        const char* p = cursor;
        while (p < line_end && (*p == ' ' || *p == '\t')) ++p;
        // Only #include "file" is resolved; #include <...> lines (the C++ side of shared headers, inside
        // #ifdef __cplusplus) pass through untouched to the GLSL preprocessor, which skips them.
        static const char kInclude[] = "#include \"";
        if (size_t(line_end - p) > sizeof kInclude && std::strncmp(p, kInclude, sizeof kInclude - 1) == 0) {
            const char* open = static_cast<const char*>(std::memchr(p, '"', size_t(line_end - p)));
            const char* close = open ? static_cast<const char*>(std::memchr(open + 1, '"', size_t(line_end - open - 1)))
                                     : nullptr;
            if (!open || !close) {
                return Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "malformed #include in %s line %d", file.path, line);
            }
            int child = find_shader(open + 1, size_t(close - open - 1));
            if (child < 0) {
                return Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "%s line %d includes unknown file '%.*s'", file.path,
                                   line, int(close - open - 1), open + 1);
            }
            if (!(*included)[size_t(child)]) {
                Error error = expand(child, depth + 1, included, out);
                if (error) return error;
            }
            std::snprintf(marker, sizeof marker, "#line %d %d\n", line + 1, index);
            out->append(marker);
        } else {
            out->append(cursor, size_t(line_end - cursor));
            out->push_back('\n');
        }
        cursor = eol ? eol + 1 : end;
        ++line;
    }
    return Error();
}

HostString read_log(const Table& gl, GLuint object, bool program, const AllocatorCallbacks& alloc) {
    GLint length = 0;
    if (program) gl.GetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
    else gl.GetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    HostString log{HostAllocator<char>(&alloc)};
    if (length <= 1) return log;
    log.resize(size_t(length));
    if (program) gl.GetProgramInfoLog(object, length, nullptr, &log[0]);
    else gl.GetShaderInfoLog(object, length, nullptr, &log[0]);
    log.resize(std::strlen(log.c_str()));
    return log;
}

}  // namespace

Error assemble_shader_source(const char* entry, const char* defines, HostString* out_source) {
    int index = find_shader(entry, std::strlen(entry));
    if (index < 0) return Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "no embedded shader named %s", entry);
    HostVector<char> included(kEmbeddedShaderCount, 0, HostAllocator<char>(out_source->get_allocator()));
    out_source->clear();
    out_source->append("#version 430 core\n");
    // `defines` holds "NAME VALUE" lines; each becomes a #define.
    for (const char* p = defines; p && *p;) {
        const char* eol = std::strchr(p, '\n');
        size_t length = eol ? size_t(eol - p) : std::strlen(p);
        if (length > 0) {
            out_source->append("#define ");
            out_source->append(p, length);
            out_source->push_back('\n');
        }
        p = eol ? eol + 1 : p + length;
    }
    return expand(index, 0, &included, out_source);
}

Error build_compute_program(const Table& gl, const char* entry, const char* defines, const AllocatorCallbacks& alloc,
                            obscura_log_fn log, void* log_user_data, Object* out_program) {
    HostString source{HostAllocator<char>(&alloc)};
    Error error = assemble_shader_source(entry, defines, &source);
    if (error) return error;

    GLuint shader = gl.CreateShader(GL_COMPUTE_SHADER);
    const GLchar* text = source.c_str();
    gl.ShaderSource(shader, 1, &text, nullptr);
    gl.CompileShader(shader);
    GLint compiled = GL_FALSE;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
    if (!compiled) {
        HostString message = read_log(gl, shader, false, alloc);
        gl.DeleteShader(shader);
        if (log) {
            HostString full{HostAllocator<char>(&alloc)};
            full.append("compiling ").append(entry).append(" failed (#line file numbers index sdk/glsl files):\n");
            full.append(message);
            log(OBSCURA_LOG_ERROR, OBSCURA_STATUS_SHADER_COMPILE_FAILED, full.c_str(), log_user_data);
        }
        return Error::make(OBSCURA_STATUS_SHADER_COMPILE_FAILED, "compiling %s failed: %s", entry, message.c_str());
    }
    GLuint program = gl.CreateProgram();
    gl.AttachShader(program, shader);
    gl.LinkProgram(program);
    gl.DetachShader(program, shader);
    gl.DeleteShader(shader);
    GLint linked = GL_FALSE;
    gl.GetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
        HostString message = read_log(gl, program, true, alloc);
        gl.DeleteProgram(program);
        if (log) log(OBSCURA_LOG_ERROR, OBSCURA_STATUS_SHADER_COMPILE_FAILED, message.c_str(), log_user_data);
        return Error::make(OBSCURA_STATUS_SHADER_COMPILE_FAILED, "linking %s failed: %s", entry, message.c_str());
    }
    *out_program = Object(&gl, ObjectKind::Program, program);
    return Error();
}

}  // namespace obscura::gl
