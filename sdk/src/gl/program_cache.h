// The last few programs of a pass whose settings are compiled in (CPU rasterisers run both sides of a branch, even
// on a uniform; constant loop counts unroll), by their key. A host that toggles a setting back and forth compiles
// nothing again; one that sweeps a setting (a tuning session in the viewer) holds at most kCapacity programs, not one
// per value it ever tried. Fixed storage: the cache itself allocates nothing.
#ifndef OBSCURA_GL_PROGRAM_CACHE_H
#define OBSCURA_GL_PROGRAM_CACHE_H

#include <cstdint>
#include <cstring>
#include <utility>

#include "error.h"
#include "gl/gl_objects.h"

namespace obscura::gl {

// A program's #define lines as a cache key: fixed storage, zero-filled, compared as text.
struct DefineLines {
    char text[384] = {};
    bool operator==(const DefineLines& other) const { return std::strcmp(text, other.text) == 0; }
};

// How many variants a pass keeps: a host may render several configurations of one method every frame (views with
// their own presets, bent normals on one of them), and each beyond the capacity would be compiled again every frame,
// seconds on a CPU rasteriser; a sweep of a setting holds this many programs, not one per value it tried.
constexpr int kProgramVariantsKept = 8;

template <class Key, int kCapacity = kProgramVariantsKept>
class ProgramCache {
public:
    // The program for `key`: the cached one, or the one `build(gl::Object*)` makes (its Error returned as it is), kept
    // in place of the least recently used.
    template <class Build>
    Error get(const Key& key, Build&& build, GLuint* out_program) {
        ++clock_;
        Slot* victim = nullptr;
        for (Slot& slot : slots_) {
            if (slot.program && slot.key == key) {
                slot.used = clock_;
                *out_program = slot.program.name();
                return Error();
            }
            if (!victim || rank(slot) < rank(*victim)) victim = &slot;
        }
        Object program;
        Error error = build(&program);
        if (error) return error;
        victim->key = key;
        victim->program = std::move(program);
        victim->used = clock_;
        *out_program = victim->program.name();
        return Error();
    }
    // The cached program for `key`, or 0.
    GLuint find(const Key& key) const {
        for (const Slot& slot : slots_) {
            if (slot.program && slot.key == key) return slot.program.name();
        }
        return 0;
    }
    int size() const {
        int count = 0;
        for (const Slot& slot : slots_) count += slot.program ? 1 : 0;
        return count;
    }

private:
    struct Slot {
        Key key{};
        Object program;
        uint64_t used = 0;
    };
    // Empty slots first, then the least recently used.
    static uint64_t rank(const Slot& slot) { return slot.program ? slot.used : 0; }
    Slot slots_[kCapacity];
    uint64_t clock_ = 0;
};

}  // namespace obscura::gl

#endif  // OBSCURA_GL_PROGRAM_CACHE_H
