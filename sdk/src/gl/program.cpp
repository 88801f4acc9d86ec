#include "gl/program.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <new>
#include <utility>

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

// Stands in for the source string in a first pass that only measures it, so the string is allocated once at its
// final size (a source is 20-60 KB: appended to a growing string it took a dozen reallocations).
struct LengthCounter {
    size_t length = 0;
    void append(const char* text) { length += std::strlen(text); }
    void append(const char*, size_t count) { length += count; }
    void push_back(char) { ++length; }
};

// Appends shader `index` to `out`, expanding includes. Each file appears once (include guards are
// implicit); #line <line> <file index> keeps driver messages pointing at the original file.
template <class Sink>
Error expand(int index, int depth, HostVector<char>* included, Sink* out) {
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

namespace {

// The version line, `defines` ("NAME VALUE" lines, each made a #define) and the expanded entry, into `out`.
template <class Sink>
Error assemble(int index, const char* defines, HostVector<char>* included, Sink* out) {
    std::fill(included->begin(), included->end(), char(0));
    out->append("#version 430 core\n");
    for (const char* p = defines; p && *p;) {
        const char* eol = std::strchr(p, '\n');
        size_t length = eol ? size_t(eol - p) : std::strlen(p);
        if (length > 0) {
            out->append("#define ");
            out->append(p, length);
            out->push_back('\n');
        }
        p = eol ? eol + 1 : p + length;
    }
    return expand(index, 0, included, out);
}

}  // namespace

Error assemble_shader_source(const char* entry, const char* defines, HostString* out_source) {
    int index = find_shader(entry, std::strlen(entry));
    if (index < 0) return Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "no embedded shader named %s", entry);
    HostVector<char> included(kEmbeddedShaderCount, 0, HostAllocator<char>(out_source->get_allocator()));
    LengthCounter counter;
    Error error = assemble(index, defines, &included, &counter);
    if (error) return error;
    out_source->clear();
    out_source->reserve(counter.length);
    return assemble(index, defines, &included, out_source);
}

namespace {

// build_compute_program without the catch: the shader and program are owned (deleted on every way out, an exception
// from the host allocator included) until the linked program is handed over.
// A driver that ran out of memory compiling or linking (or lost the context meanwhile) fails the build with an empty
// log: that is what failed, not the source. The errors GL left for the step `doing` ("compiling", "linking") as that
// status (reported once, not as a compile failure in the log), or no error if neither.
Error driver_failure(const Table& gl, const char* doing, const char* entry) {
    const GLenum gl_error = take_errors(gl);
    if (gl_error == GL_OUT_OF_MEMORY) {
        return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "%s %s ran out of memory (GL_OUT_OF_MEMORY)", doing, entry);
    }
    if (gl_error == kGlContextLostError) {
        return Error::make(OBSCURA_STATUS_CONTEXT_LOST, "the OpenGL context was lost while %s %s", doing, entry);
    }
    return Error();
}

// A compile or link the driver refused: its whole log goes to the log callback as a warning (the header's "shader
// logs"; a log can outgrow an Error's message), and the Error names the step, the entry and the log's first error
// line. The host's callback then receives that error once, from the call that returns it (Context::report): it
// received the whole log twice as errors when this function logged it as an error too.
Error build_failure(obscura_log_fn log, void* log_user_data, const char* doing, const char* entry,
                    const HostString& driver_log) {
    if (log) {
        HostString full{driver_log.get_allocator()};
        full.append(doing).append(" ").append(entry).append(": the driver's log (#line file numbers index sdk/glsl files):\n");
        full.append(driver_log);
        log(OBSCURA_LOG_WARNING, OBSCURA_STATUS_SHADER_COMPILE_FAILED, full.c_str(), log_user_data);
    }
    // The first line that names an error (drivers may lead with warnings), else the first line.
    const char* text = driver_log.c_str();
    const char* line = text;
    for (const char* p = text; *p;) {
        const char* eol = std::strchr(p, '\n');
        const size_t length = eol ? size_t(eol - p) : std::strlen(p);
        // "error", "Error" or "ERROR" (not "rror": "mirror" would do).
        bool names_error = false;
        for (const char* word : {"error", "Error", "ERROR"}) {
            const char* found = std::strstr(p, word);
            names_error = names_error || (found && found < p + length);
        }
        if (names_error) {
            line = p;
            break;
        }
        p = eol ? eol + 1 : p + length;
    }
    const char* end = std::strchr(line, '\n');
    const int length = int(end ? end - line : std::strlen(line));
    return Error::make(OBSCURA_STATUS_SHADER_COMPILE_FAILED, "%s %s failed: %.*s%s", doing, entry, length, line,
                       log ? " (the driver's whole log went to the log callback)" : "");
}

Error build_program(const Table& gl, const char* entry, const char* defines, const AllocatorCallbacks& alloc,
                    obscura_log_fn log, void* log_user_data, Object* out_program) {
    HostString source{HostAllocator<char>(&alloc)};
    Error error = assemble_shader_source(entry, defines, &source);
    if (error) return error;

    Object shader(&gl, ObjectKind::Shader, gl.CreateShader(GL_COMPUTE_SHADER));
    const GLchar* text = source.c_str();
    gl.ShaderSource(shader.name(), 1, &text, nullptr);
    gl.CompileShader(shader.name());
    GLint compiled = GL_FALSE;
    gl.GetShaderiv(shader.name(), GL_COMPILE_STATUS, &compiled);
    if (!compiled) {
        error = driver_failure(gl, "compiling", entry);
        if (error) return error;
        return build_failure(log, log_user_data, "compiling", entry, read_log(gl, shader.name(), false, alloc));
    }
    Object program(&gl, ObjectKind::Program, gl.CreateProgram());
    gl.AttachShader(program.name(), shader.name());
    gl.LinkProgram(program.name());
    gl.DetachShader(program.name(), shader.name());
    shader.reset();
    GLint linked = GL_FALSE;
    gl.GetProgramiv(program.name(), GL_LINK_STATUS, &linked);
    if (!linked) {
        error = driver_failure(gl, "linking", entry);
        if (error) return error;
        return build_failure(log, log_user_data, "linking", entry, read_log(gl, program.name(), true, alloc));
    }
    *out_program = std::move(program);
    return Error();
}

}  // namespace

Error build_compute_program(const Table& gl, const char* entry, const char* defines, const AllocatorCallbacks& alloc,
                            obscura_log_fn log, void* log_user_data, Object* out_program) {
    // The source and logs come from the host allocator, whose failure throws std::bad_alloc (HostAllocator). Caught
    // here, so that every caller sees an Error and its own failure path runs: a pass that builds several programs
    // in turn drops the ones it made (FFAO's table program once stayed without its scan and prefix programs, and
    // every later frame dispatched program 0).
    try {
        return build_program(gl, entry, defines, alloc, log, log_user_data, out_program);
    } catch (const std::bad_alloc&) {
        return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "building %s: the host allocator returned NULL", entry);
    }
}

}  // namespace obscura::gl
