// The method registry: one row per method, the only place the SDK lists its methods. Everything that
// depends on the method (its name, its settings block and metadata, how its derived settings resolve, the
// falloff it is compared with, the passes it times, the technique that renders it) is read from its row, so
// adding a method is: its settings struct in obscura.h, its row in method_registry.cpp, its source in
// sdk/src/methods/ and its shaders (docs/architecture.md).
#ifndef OBSCURA_METHOD_REGISTRY_H
#define OBSCURA_METHOD_REGISTRY_H

#include <cstddef>

#include "error.h"
#include "host_allocator.h"
#include "pass_id.h"

namespace obscura {

class Technique;

struct MethodDescriptor {
    obscura_method method;
    const char* name;                    // obscura_method_name, spec names in the samples
    size_t settings_offset;              // its block inside obscura_settings
    size_t settings_size;
    const obscura_setting_info* settings;  // its metadata rows (offsets inside obscura_settings)
    uint32_t setting_count;
    // Derives the block's dependent values (zero "derive" fields) in `resolved`, whose fields are already
    // defaulted and range-checked, and checks what the per-field ranges cannot. `in` is the caller's struct.
    Error (*derive)(const obscura_settings& in, obscura_settings* resolved);
    // The REFERENCE falloff (kind, radius, C, decay rate, table, thickness) the method weighs occluders with,
    // from resolved settings; null for REFERENCE itself (its settings are the reference).
    void (*reference_falloff)(const obscura_settings& resolved, obscura_reference_settings* reference);
    // The passes its frames can report, in the order they run (a frame reports a subset).
    const PassId* passes;
    uint32_t pass_count;
    Technique* (*create_technique)(const AllocatorCallbacks& alloc);
    bool bent_normals = false;           // writes output.bent_normal_texture (obscura_method_writes_bent_normals)
    // Derives what depends on the GL renderer (zero fields the context settles when it renders), for
    // obscura_resolve_settings with a context; null if nothing does.
    void (*derive_for_renderer)(bool cpu_renderer, obscura_settings* resolved) = nullptr;
    // Fields added after the block's layout was released (obscura_ffao_added_settings): a second block at the end of
    // obscura_settings, where hosts built against older headers have none. Its rows are among `settings`.
    size_t added_offset = 0;
    size_t added_size = 0;
};

// Every method, in obscura_method order (OBSCURA_METHOD_DEFAULT excluded).
const MethodDescriptor* const* method_descriptors(uint32_t* count);

// The row of a method (OBSCURA_METHOD_DEFAULT: HBAO's); null for a value that is no method. Takes the enum by
// reference and reads its bytes as an int: any value a C host passes is safe (loading an out-of-range value as
// the C++ enum would be undefined).
const MethodDescriptor* find_method(const obscura_method& method);
const MethodDescriptor* find_method_value(int32_t value);

}  // namespace obscura

#endif  // OBSCURA_METHOD_REGISTRY_H
