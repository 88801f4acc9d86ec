// The C boundary: argument checks that need no GL, status mapping, and nothing else. Every call
// below either returns a status with a message or forwards to Context; no exception crosses it.
#include <cstring>
#include <new>

#include "context.h"
#include "falloff.h"
#include "host_enum.h"
#include "method_registry.h"
#include "settings.h"
#include "shared_settings.h"

using obscura::Context;
using obscura::Error;

namespace {

#define OBSCURA_STATUS_STRING_ENTRY_(name, value, desc) "OBSCURA_STATUS_" #name ": " desc,
const char* const kStatusStrings[] = {OBSCURA_STATUS_LIST(OBSCURA_STATUS_STRING_ENTRY_)};
#undef OBSCURA_STATUS_STRING_ENTRY_

Context* as_context(obscura_context* context) { return static_cast<Context*>(context); }

// The message of this thread's last call made without a context (obscura_get_last_error(NULL)): the settings
// functions need none, and tools that have no GL context still get the reason for a refusal.
thread_local char t_last_error[1024] = "";

obscura_status report_without_context(const Error& error) {
    std::snprintf(t_last_error, sizeof t_last_error, "%s", error.ok() ? "" : error.message());
    return error.status();
}

// An argument error of a call that names a context goes to that context (its last error, its log callback);
// without one, to this thread's.
obscura_status report_to(const obscura_context* context, const Error& error) {
    // Reporting writes the context's last-error record only, which obscura_get_last_error reads back.
    return context ? const_cast<Context*>(static_cast<const Context*>(context))->report(error)
                   : report_without_context(error);
}

// Runs `body` (returning Error) and maps its result and any exception to a status on `context`.
template <class Body>
obscura_status guarded(Context* context, Body&& body) {
    Error error;
    try {
        error = body();
    } catch (const std::bad_alloc&) {
        error = Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "the allocator returned NULL");
    } catch (...) {
        error = Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "unexpected exception inside Obscura");
    }
    return context ? context->report(error) : report_without_context(error);
}

Error check_struct(uint32_t struct_size, size_t expected, const char* name) {
    if (struct_size != expected) {
        return Error::make(OBSCURA_STATUS_INVALID_STRUCT_SIZE,
                           "%s.struct_size is %u but this library expects %u (set it to sizeof(%s))", name,
                           struct_size, unsigned(expected), name);
    }
    return Error();
}

}  // namespace

extern "C" {

OBSCURA_API uint32_t obscura_version(void) { return OBSCURA_VERSION; }

OBSCURA_API const char* obscura_status_string(obscura_status status) {
    const int32_t value = obscura::stored_enum(status);
    if (value < 0 || value >= int32_t(OBSCURA_STATUS_COUNT_)) return "OBSCURA_STATUS_?: unknown status code";
    return kStatusStrings[value];
}

OBSCURA_API const char* obscura_method_name(obscura_method method) {
    const obscura::MethodDescriptor* row = obscura::find_method(method);
    return row ? row->name : nullptr;
}

// Every method with a registry row is implemented; the function remains for methods a build or a later
// version does not have.
OBSCURA_API int obscura_method_available(obscura_method method) { return obscura::find_method(method) ? 1 : 0; }

OBSCURA_API int obscura_method_writes_bent_normals(obscura_method method) {
    const obscura::MethodDescriptor* row = obscura::find_method(method);
    return row && row->bent_normals ? 1 : 0;
}

OBSCURA_API obscura_status obscura_create_context(const obscura_context_desc* desc, obscura_context** out_context) {
    if (out_context) *out_context = nullptr;
    auto fail = [&](const Error& error) {
        if (desc && desc->log) desc->log(OBSCURA_LOG_ERROR, error.status(), error.message(), desc->log_user_data);
        return report_without_context(error);
    };
    if (!desc || !out_context) {
        return fail(Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_create_context: desc and out_context are required"));
    }
    Error error = check_struct(desc->struct_size, sizeof(obscura_context_desc), "obscura_context_desc");
    if (error) return fail(error);
    // Same major version, and a header no newer than the library (its structs would be larger). 0 is a field left
    // unset (the header has always been at least 0.1: 100), not a version.
    if (desc->header_version == 0 || desc->header_version / 10000 != OBSCURA_VERSION_MAJOR ||
        desc->header_version > OBSCURA_VERSION) {
        return fail(Error::make(OBSCURA_STATUS_VERSION_MISMATCH,
                                "header version %u is not compatible with library version %u", desc->header_version,
                                unsigned(OBSCURA_VERSION)));
    }
    if ((desc->get_proc_address == nullptr) == (desc->get_proc_address_with_user_data == nullptr)) {
        return fail(Error::make(OBSCURA_STATUS_NULL_ARGUMENT,
                                "obscura_context_desc needs exactly one of get_proc_address and "
                                "get_proc_address_with_user_data"));
    }
    if ((desc->allocator.alloc == nullptr) != (desc->allocator.free == nullptr)) {
        return fail(Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_allocator needs both alloc and free, or neither"));
    }
    // Unknown bits are refused as obscura_input's and obscura_settings' are: a flag of a later header (or a stray
    // value) would otherwise be ignored without a word.
    constexpr uint32_t kKnownFlags = OBSCURA_CONTEXT_FLAG_SYNC_TIMING | OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES |
                                     OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS;
    if ((desc->flags & ~kKnownFlags) != 0) {
        return fail(Error::make(OBSCURA_STATUS_INVALID_SETTING, "obscura_context_desc.flags = 0x%x has unknown bits",
                                unsigned(desc->flags)));
    }
    Context* context = nullptr;
    try {
        error = Context::create(*desc, &context);
    } catch (const std::bad_alloc&) {
        error = Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "the allocator returned NULL");
    } catch (...) {
        error = Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "unexpected exception inside Obscura");
    }
    if (error) return fail(error);
    *out_context = context;
    return report_without_context(Error());
}

OBSCURA_API void obscura_destroy_context(obscura_context* context) { Context::destroy(as_context(context)); }

OBSCURA_API obscura_status obscura_create_view(obscura_context* context, obscura_view** out_view) {
    if (out_view) *out_view = nullptr;
    if (!context || !out_view) {
        return report_to(context,
                         Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_create_view: context and out_view are required"));
    }
    Context* ctx = as_context(context);
    return guarded(ctx, [&]() -> Error {
        obscura::View* view = nullptr;
        Error error = ctx->create_view(&view);
        if (!error) *out_view = view;
        return error;
    });
}

OBSCURA_API obscura_status obscura_destroy_view(obscura_context* context, obscura_view* view) {
    if (!context) {
        return report_without_context(Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_destroy_view: context is NULL"));
    }
    if (!view) return OBSCURA_OK;
    Context* ctx = as_context(context);
    return guarded(ctx, [&]() -> Error { return ctx->destroy_view(view); });
}

OBSCURA_API const char* obscura_get_last_error(const obscura_context* context) {
    if (!context) return t_last_error;
    return static_cast<const Context*>(context)->last_error();
}

namespace {

// The bodies of the sized and the 0.3 entry points. The method is taken by reference and only read as an int
// (find_method): a C host may pass any value, and loading one outside the enum as the C++ type is undefined.
obscura_status default_settings_of_size(const obscura_method& method, obscura_settings* out, uint32_t out_size) {
    if (!out) return report_without_context(Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_default_settings: out is NULL"));
    if (!obscura::is_known_settings_size(out_size)) {
        return report_without_context(Error::make(OBSCURA_STATUS_INVALID_STRUCT_SIZE,
                                                  "obscura_default_settings: %u is the obscura_settings size of no "
                                                  "released obscura.h",
                                                  out_size));
    }
    obscura_settings defaults;
    const Error error = obscura::default_settings(method, &defaults);
    if (!error) obscura::write_host_settings(defaults, out, out_size);
    return report_without_context(error);
}

obscura_status setting_infos_of_size(const obscura_method& method, const obscura_setting_info** out_infos,
                                     uint32_t* out_count, uint32_t info_size) {
    if (!out_infos || !out_count) {
        return report_without_context(
            Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_get_setting_infos: out_infos and out_count are required"));
    }
    if (!obscura::find_method(method)) {
        return report_without_context(Error::make(OBSCURA_STATUS_INVALID_ENUM, "obscura_get_setting_infos: %d is not an "
                                                  "obscura_method", int(obscura::stored_enum(method))));
    }
    if (info_size == sizeof(obscura::SettingInfo03)) {
        // The caller's obscura_setting_info is the 0.3 struct, which is what this table holds.
        *out_infos = reinterpret_cast<const obscura_setting_info*>(obscura::setting_infos_03(method, out_count));
    } else if (info_size == sizeof(obscura::SettingInfo04)) {
        // A 0.4 caller: its layout, and the rows its obscura_settings has fields for.
        *out_infos = reinterpret_cast<const obscura_setting_info*>(obscura::setting_infos_04(method, out_count));
    } else if (info_size == sizeof(obscura_setting_info)) {
        *out_infos = obscura::setting_infos(method, out_count);
    } else {
        return report_without_context(Error::make(OBSCURA_STATUS_INVALID_STRUCT_SIZE,
                                                  "obscura_get_setting_infos: %u is the obscura_setting_info size of no "
                                                  "released obscura.h",
                                                  info_size));
    }
    return report_without_context(Error());
}

}  // namespace

OBSCURA_API obscura_status obscura_default_settings_sized(obscura_method method, obscura_settings* out,
                                                          uint32_t out_size) {
    return default_settings_of_size(method, out, out_size);
}

OBSCURA_API obscura_status obscura_get_setting_infos_sized(obscura_method method,
                                                           const obscura_setting_info** out_infos,
                                                           uint32_t* out_count, uint32_t info_size) {
    return setting_infos_of_size(method, out_infos, out_count, info_size);
}

// The 0.3 ABI: binaries built against 0.3 call these names; the header's macros of the same names call the
// sized entry points.
#undef obscura_default_settings
OBSCURA_API obscura_status(obscura_default_settings)(obscura_method method, obscura_settings* out) {
    return default_settings_of_size(method, out, obscura::settings_size_03());
}

#undef obscura_get_setting_infos
OBSCURA_API obscura_status(obscura_get_setting_infos)(obscura_method method, const obscura_setting_info** out_infos,
                                                      uint32_t* out_count) {
    return setting_infos_of_size(method, out_infos, out_count, uint32_t(sizeof(obscura::SettingInfo03)));
}

OBSCURA_API obscura_status obscura_get_shared_setting_infos(const obscura_setting_info** out_infos,
                                                              uint32_t* out_count) {
    if (!out_infos || !out_count) {
        return report_without_context(Error::make(OBSCURA_STATUS_NULL_ARGUMENT,
                                                  "obscura_get_shared_setting_infos: out_infos and out_count are required"));
    }
    *out_infos = obscura::shared_setting_infos(out_count);
    return report_without_context(Error());
}

OBSCURA_API obscura_status obscura_resolve_settings(obscura_context* context, const obscura_settings* in,
                                                    obscura_settings* out) {
    return guarded(as_context(context), [&]() -> Error {
        if (!in || !out) return Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_resolve_settings: in and out are required");
        const uint32_t size = in->struct_size;
        obscura_settings whole, resolved;
        Error error = obscura::read_host_settings(in, &whole, "obscura_resolve_settings");
        if (!error) error = obscura::resolve_settings(whole, &resolved);
        if (!error && context) obscura::derive_for_renderer(as_context(context)->cpu_renderer(), &resolved);
        if (!error) obscura::write_host_settings(resolved, out, size);
        return error;
    });
}

OBSCURA_API obscura_status obscura_reference_settings_for(const obscura_settings* method_settings,
                                                          obscura_settings* out) {
    if (!method_settings || !out) {
        return report_without_context(Error::make(OBSCURA_STATUS_NULL_ARGUMENT,
                                                  "obscura_reference_settings_for: method_settings and out are required"));
    }
    const uint32_t size = method_settings->struct_size;
    obscura_settings whole, reference;
    Error error = obscura::read_host_settings(method_settings, &whole, "obscura_reference_settings_for");
    if (!error) error = obscura::reference_settings_for(whole, &reference);
    if (!error) obscura::write_host_settings(reference, out, size);
    return report_without_context(error);
}

OBSCURA_API obscura_status obscura_evaluate_falloff(const obscura_settings* method_settings, const float* distances,
                                                    float* rho, uint32_t count) {
    if (!method_settings || (count > 0 && (!distances || !rho))) {
        return report_without_context(Error::make(OBSCURA_STATUS_NULL_ARGUMENT,
                                                  "obscura_evaluate_falloff: method_settings, distances and rho are "
                                                  "required"));
    }
    obscura_settings whole, reference;
    Error error = obscura::read_host_settings(method_settings, &whole, "obscura_evaluate_falloff");
    if (!error) error = obscura::reference_settings_for(whole, &reference);
    if (error) return report_without_context(error);
    const obscura::FalloffParameters falloff = obscura::falloff_parameters(reference.reference);
    for (uint32_t i = 0; i < count; ++i) rho[i] = float(obscura::falloff_value(falloff, double(distances[i])));
    return report_without_context(Error());
}

OBSCURA_API obscura_status obscura_set_setting(obscura_settings* settings, const char* name, double value) {
    if (!settings || !name) {
        return report_without_context(
            Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_set_setting: settings and name are required"));
    }
    const uint32_t size = settings->struct_size;
    obscura_settings whole;
    Error error = obscura::read_host_settings(settings, &whole, "obscura_set_setting");
    if (!error) error = obscura::set_setting(&whole, name, value, size);
    if (!error) obscura::write_host_settings(whole, settings, size);
    return report_without_context(error);
}

OBSCURA_API obscura_status obscura_get_setting(const obscura_settings* settings, const char* name, double* out_value) {
    if (!settings || !name || !out_value) {
        return report_without_context(
            Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_get_setting: settings, name and out_value are required"));
    }
    obscura_settings whole;
    Error error = obscura::read_host_settings(settings, &whole, "obscura_get_setting");
    if (!error) error = obscura::get_setting(whole, name, out_value);
    return report_without_context(error);
}

OBSCURA_API obscura_status obscura_render(obscura_context* context, const obscura_input* input,
                                          const obscura_settings* settings, const obscura_output* output) {
    if (!context) return report_without_context(Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_render: context is NULL"));
    Context* ctx = as_context(context);
    return guarded(ctx, [&]() -> Error {
        if (!input || !settings || !output) {
            return Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_render: input, settings and output are required");
        }
        // obscura_input: this header's, or 0.4's (without the temporal fields, which then read 0).
        obscura_input whole_input;
        std::memset(&whole_input, 0, sizeof whole_input);
        // (Its last field is normal_texture: the 0.4 struct ends there, before the padding that aligns `view`.)
        const uint32_t input_size_04 = uint32_t(offsetof(obscura_input, normal_texture) + sizeof(uint32_t));
        Error error = input->struct_size == input_size_04
                          ? Error()
                          : check_struct(input->struct_size, sizeof(obscura_input), "obscura_input");
        if (!error) {
            std::memcpy(&whole_input, input, input->struct_size);
            whole_input.struct_size = sizeof whole_input;
        }
        // obscura_output: this header's, or 0.4's (without bent_normal_texture, which then reads 0).
        obscura_output whole_output;
        std::memset(&whole_output, 0, sizeof whole_output);
        const uint32_t output_size_04 = uint32_t(offsetof(obscura_output, bent_normal_texture));
        if (!error && output->struct_size != output_size_04) {
            error = check_struct(output->struct_size, sizeof(obscura_output), "obscura_output");
        }
        if (!error) std::memcpy(&whole_output, output, output->struct_size);
        obscura_settings whole;
        if (!error) error = obscura::read_host_settings(settings, &whole, "obscura_render");
        if (error) return error;
        return ctx->render(whole_input, whole, whole_output);
    });
}

OBSCURA_API obscura_status obscura_prepare(obscura_context* context, int32_t depth_width, int32_t depth_height,
                                           const obscura_settings* settings) {
    if (!context) return report_without_context(Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_prepare: context is NULL"));
    Context* ctx = as_context(context);
    return guarded(ctx, [&]() -> Error {
        if (!settings) return Error::make(OBSCURA_STATUS_NULL_ARGUMENT, "obscura_prepare: settings is required");
        obscura_settings whole;
        Error error = obscura::read_host_settings(settings, &whole, "obscura_prepare");
        if (error) return error;
        return ctx->prepare(depth_width, depth_height, whole);
    });
}

OBSCURA_API void obscura_release_resources(obscura_context* context) {
    if (context) as_context(context)->release_resources_from_host();
}

OBSCURA_API obscura_status obscura_get_timings(obscura_context* context, obscura_timing* out, uint32_t capacity,
                                               uint32_t* out_count, uint64_t* out_frame_index) {
    if (!context || !out_count || (!out && capacity > 0)) {
        return report_to(context, Error::make(OBSCURA_STATUS_NULL_ARGUMENT,
                                              "obscura_get_timings: context, out_count (and out) are required"));
    }
    Context* ctx = as_context(context);
    uint64_t frame_index = 0;
    const Error error = ctx->timings(out, capacity, out_count, &frame_index);
    if (out_frame_index) *out_frame_index = frame_index;
    return error ? ctx->report(error) : OBSCURA_OK;
}

OBSCURA_API obscura_status obscura_get_memory_usage(const obscura_context* context, uint64_t* out_bytes) {
    if (!context || !out_bytes) {
        return report_to(context, Error::make(OBSCURA_STATUS_NULL_ARGUMENT,
                                              "obscura_get_memory_usage: context and out_bytes are required"));
    }
    *out_bytes = static_cast<const Context*>(context)->memory_bytes();
    return OBSCURA_OK;
}

}  // extern "C"
