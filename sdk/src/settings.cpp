#include "settings.h"

#include "host_enum.h"
#include "method_registry.h"
#include "shared_settings.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

namespace obscura {
namespace {

template <class T>
T* field_at(obscura_settings* settings, size_t offset) {
    return reinterpret_cast<T*>(reinterpret_cast<unsigned char*>(settings) + offset);
}
template <class T>
const T* field_at(const obscura_settings* settings, size_t offset) {
    return reinterpret_cast<const T*>(reinterpret_cast<const unsigned char*>(settings) + offset);
}

// The method field as the int the host stored (host_enum.h).
int32_t stored_method(const obscura_settings& settings) { return stored_enum(settings.method); }

obscura_method resolve_method_value(int32_t value) {
    const MethodDescriptor* row = find_method_value(value);
    return row ? row->method : OBSCURA_METHOD_COUNT_;
}

// Calls f(block name, rows, count) for every method's table, then for the rows every method shares (temporal
// accumulation, resolution), whose names carry their block ("temporal.enabled").
template <class F>
void for_each_table(F f) {
    uint32_t method_count = 0;
    const MethodDescriptor* const* methods = method_descriptors(&method_count);
    for (uint32_t m = 0; m < method_count; ++m) f(methods[m]->name, methods[m]->settings, methods[m]->setting_count);
    uint32_t shared_count = 0;
    const obscura_setting_info* shared = shared_setting_infos(&shared_count);
    f("obscura_settings", shared, shared_count);
}

// The method's row of that name, or the shared row.
const obscura_setting_info* find_info(obscura_method method, const char* name) {
    uint32_t count = 0;
    const obscura_setting_info* infos = setting_infos(method, &count);
    for (uint32_t i = 0; i < count; ++i) {
        if (std::strcmp(infos[i].name, name) == 0) return &infos[i];
    }
    infos = shared_setting_infos(&count);
    for (uint32_t i = 0; i < count; ++i) {
        if (std::strcmp(infos[i].name, name) == 0) return &infos[i];
    }
    return nullptr;
}

// The block a row belongs to, as messages name it: the method's ("hbao"), or "obscura_settings" for the rows every
// method shares ("obscura_settings.temporal.max_frames": the C field's path).
const char* block_name(obscura_method method, const obscura_setting_info& info) {
    uint32_t count = 0;
    const obscura_setting_info* shared = shared_setting_infos(&count);
    if (&info >= shared && &info < shared + count) return "obscura_settings";
    // FFAO's rows added after its block's layout was released live in a block of their own.
    const size_t added = offsetof(obscura_settings, ffao_added);
    if (info.offset >= added && info.offset < added + sizeof(obscura_ffao_added_settings)) return "ffao_added";
    return obscura_method_name(method);
}

// The field's bytes end within a struct of `size` bytes (an older header's obscura_settings).
bool field_fits(const obscura_setting_info& info, size_t size) {
    const size_t bytes = info.type == OBSCURA_SETTING_FLOAT_ARRAY ? info.value_count * sizeof(float) : 4;
    return info.offset + bytes <= size;
}

bool is_derived(const obscura_setting_info& info) { return (info.flags & OBSCURA_SETTING_FLAG_DERIVED) != 0; }

// A zero that, with OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE, is the value 0 rather than the default.
bool zero_can_be_value(const obscura_setting_info& info) {
    return !is_derived(info) && info.min_value <= 0.0 && info.max_value >= 0.0 && info.default_value != 0.0 &&
           (info.type == OBSCURA_SETTING_FLOAT || info.type == OBSCURA_SETTING_INT);
}

// Stored value of a field as a double, with 0 meaning "default" (toggles: 0 default, 1 on, 2 off). Array
// settings read 0 (their values are checked by the method's derive step).
double stored_value(const obscura_settings& settings, const obscura_setting_info& info) {
    switch (info.type) {
        case OBSCURA_SETTING_FLOAT: return *field_at<float>(&settings, info.offset);
        case OBSCURA_SETTING_INT:
        case OBSCURA_SETTING_ENUM: return *field_at<int32_t>(&settings, info.offset);
        case OBSCURA_SETTING_TOGGLE: {
            int32_t toggle = *field_at<int32_t>(&settings, info.offset);
            return toggle == OBSCURA_TOGGLE_DEFAULT ? 0.0 : toggle == OBSCURA_TOGGLE_ON ? 1.0 : -1.0;
        }
        case OBSCURA_SETTING_FLOAT_ARRAY: return 0.0;
    }
    return 0.0;
}

// `block` names the settings block in messages ("hbao"; "obscura_settings" for the shared rows).
Error check_value(const obscura_setting_info& info, const char* block, double value) {
    if (!std::isfinite(value)) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s is %g; it must be finite", block, info.name, value);
    }
    // Float settings live in floats: compare the value a float field holds (or will hold) with the range's edges
    // as floats hold them. Compared as doubles, the documented edges themselves were refused once stored:
    // float(1e-8) is below 1e-8 and float(0.999) above 0.999, so set_setting accepted them and resolve did not.
    // (A double beyond the float range stays as it is: converting it would be undefined, and it is out of range.)
    const bool as_float = info.type == OBSCURA_SETTING_FLOAT;
    const bool fits_float = std::fabs(value) <= double(std::numeric_limits<float>::max());
    const double stored = as_float && fits_float ? double(float(value)) : value;
    const double min_value = as_float ? double(float(info.min_value)) : info.min_value;
    const double max_value = as_float ? double(float(info.max_value)) : info.max_value;
    if (stored < min_value || stored > max_value) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s = %g is outside [%g, %g]%s%s", block, info.name,
                           value, info.min_value, info.max_value,
                           info.unit[0] ? " " : "", info.unit);
    }
    if (info.type != OBSCURA_SETTING_FLOAT && value != std::floor(value)) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s = %g must be a whole number", block, info.name,
                           value);
    }
    return Error();
}

void store_value(obscura_settings* settings, const obscura_setting_info& info, double value) {
    switch (info.type) {
        case OBSCURA_SETTING_FLOAT: *field_at<float>(settings, info.offset) = float(value); break;
        case OBSCURA_SETTING_INT:
        case OBSCURA_SETTING_ENUM: *field_at<int32_t>(settings, info.offset) = int32_t(std::lround(value)); break;
        case OBSCURA_SETTING_TOGGLE:
            *field_at<int32_t>(settings, info.offset) = value != 0.0 ? OBSCURA_TOGGLE_ON : OBSCURA_TOGGLE_OFF;
            break;
        case OBSCURA_SETTING_FLOAT_ARRAY: break;
    }
}

// The sizes of obscura_settings in the released headers: each appended a block (or a field) at the end.
constexpr uint32_t kSettingsSize01 = uint32_t(offsetof(obscura_settings, reference));  // HBAO only
constexpr uint32_t kSettingsSize02 = uint32_t(offsetof(obscura_settings, sao));        // + REFERENCE
constexpr uint32_t kSettingsSize03 = uint32_t(offsetof(obscura_settings, flags));      // + SAO, LSAO, FFAO
constexpr uint32_t kSettingsSize04 = uint32_t(offsetof(obscura_settings, gtao));       // + flags
constexpr uint32_t kSettingsSizes[] = {kSettingsSize01, kSettingsSize02, kSettingsSize03, kSettingsSize04,
                                       uint32_t(sizeof(obscura_settings))};

}  // namespace

Error check_falloff_table(const char* method, int32_t falloff, const float (&table)[OBSCURA_FALLOFF_TABLE_SIZE]) {
    if (falloff != OBSCURA_FALLOFF_TABLE) return Error();
    bool any_positive = false;
    for (int i = 0; i < OBSCURA_FALLOFF_TABLE_SIZE; ++i) {
        float value = table[i];
        if (!(value >= 0.0f && value <= 1.0f)) {
            return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.falloff_table[%d] = %g is outside [0, 1]", method, i,
                               double(value));
        }
        any_positive = any_positive || value > 0.0f;
    }
    if (!any_positive) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                           "%s.falloff is TABLE but %s.falloff_table is all zero: fill it with rho(d) at d = i/%d * "
                           "radius",
                           method, method, OBSCURA_FALLOFF_TABLE_SIZE - 1);
    }
    return Error();
}

obscura_method resolve_method(const obscura_method& method) { return resolve_method_value(stored_enum(method)); }

const obscura_setting_info* setting_infos(const obscura_method& method, uint32_t* count) {
    const MethodDescriptor* row = find_method(method);
    *count = row ? row->setting_count : 0;
    return row ? row->settings : nullptr;
}

namespace {

// A method's table in an older header's layout, built once from the rows (C++11 initialises a local static once,
// thread-safely; no heap): `convert` gives a row in that layout, or false for a row that header does not have.
template <class Row, class Convert>
const Row* older_table(const obscura_method& method, uint32_t* count, Convert convert) {
    constexpr uint32_t kMaxRows = 48;
    struct Tables {
        Row rows[OBSCURA_METHOD_COUNT_][kMaxRows] = {};
        uint32_t counts[OBSCURA_METHOD_COUNT_] = {};
    };
    static const Tables tables = [&] {
        Tables t;
        uint32_t method_count = 0;
        const MethodDescriptor* const* methods = method_descriptors(&method_count);
        for (uint32_t m = 0; m < method_count; ++m) {
            const MethodDescriptor& row = *methods[m];
            uint32_t& n = t.counts[row.method];
            for (uint32_t i = 0; i < row.setting_count && n < kMaxRows; ++i) {
                if (convert(row.settings[i], &t.rows[row.method][n])) ++n;
            }
        }
        return t;
    }();
    const MethodDescriptor* row = find_method(method);
    *count = row ? tables.counts[row->method] : 0;
    return row ? tables.rows[row->method] : nullptr;
}

// The 0.3 fields of a row, its ENUM type read as INT (0.3 had no ENUM).
SettingInfo03 as_03(const obscura_setting_info& info) {
    const obscura_setting_type type = info.type == OBSCURA_SETTING_ENUM ? OBSCURA_SETTING_INT : info.type;
    return SettingInfo03{info.name,      type,           info.default_value, info.min_value,
                         info.max_value, info.unit,      info.description,   info.offset};
}

}  // namespace

const SettingInfo04* setting_infos_04(const obscura_method& method, uint32_t* count) {
    return older_table<SettingInfo04>(method, count, [](const obscura_setting_info& info, SettingInfo04* out) {
        if (info.added_in > 400) return false;  // a 0.4 struct has no field for it
        SettingInfo03 first = as_03(info);
        first.type = info.type;  // 0.4 has ENUM
        *out = SettingInfo04{first, info.flags, info.value_count, info.value_names};
        return true;
    });
}

const SettingInfo03* setting_infos_03(const obscura_method& method, uint32_t* count) {
    return older_table<SettingInfo03>(method, count, [](const obscura_setting_info& info, SettingInfo03* out) {
        // Rows a 0.3 struct has no field for: arrays (0.4) and the rows added since.
        if (info.type == OBSCURA_SETTING_FLOAT_ARRAY || info.added_in > 300) return false;
        *out = as_03(info);
        return true;
    });
}

bool is_known_settings_size(uint32_t struct_size) {
    for (uint32_t size : kSettingsSizes) {
        if (struct_size == size) return true;
    }
    return false;
}

uint32_t settings_size_03() { return kSettingsSize03; }

Error read_host_settings(const obscura_settings* host, obscura_settings* out, const char* what) {
    uint32_t size = 0;
    std::memcpy(&size, host, sizeof size);
    if (!is_known_settings_size(size)) {
        return Error::make(OBSCURA_STATUS_INVALID_STRUCT_SIZE,
                           "%s: obscura_settings.struct_size is %u, the size of no released obscura.h (this one's is "
                           "%u: set it to sizeof(obscura_settings))",
                           what, size, unsigned(sizeof(obscura_settings)));
    }
    obscura_settings whole;
    std::memset(&whole, 0, sizeof whole);
    std::memcpy(&whole, host, size);  // an older header's struct: the fields it lacks read 0, their defaults
    whole.struct_size = sizeof whole;
    // ... except where the struct says 0 is a value (OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE, which a 0.4 struct has):
    // there the fields it lacks hold their defaults explicitly (a 0.4 host's gtao.mip_offset read 0, not 3.3).
    if (whole.flags & OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE) {
        for_each_table([&](const char*, const obscura_setting_info* rows, uint32_t count) {
            for (uint32_t i = 0; i < count; ++i) {
                if (!field_fits(rows[i], size) && zero_can_be_value(rows[i])) {
                    store_value(&whole, rows[i], rows[i].default_value);
                }
            }
        });
    }
    *out = whole;
    return Error();
}

void write_host_settings(const obscura_settings& settings, obscura_settings* host, uint32_t size) {
    obscura_settings copy = settings;
    copy.struct_size = size;
    std::memcpy(host, &copy, size);
}

Error default_settings(const obscura_method& method, obscura_settings* out) {
    const MethodDescriptor* selected = find_method(method);
    if (!selected) return Error::make(OBSCURA_STATUS_INVALID_ENUM, "%d is not an obscura_method", int(stored_enum(method)));
    obscura_settings settings;
    std::memset(&settings, 0, sizeof settings);
    settings.struct_size = sizeof settings;
    settings.method = selected->method;
    settings.flags = OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE;
    // Every method's block, so that switching `method` later starts from its defaults too. Derived fields and
    // arrays stay 0 ("derive", and a table that only the TABLE falloff reads).
    for_each_table([&](const char*, const obscura_setting_info* rows, uint32_t count) {
        for (uint32_t i = 0; i < count; ++i) {
            const obscura_setting_info& info = rows[i];
            if (!is_derived(info) && info.type != OBSCURA_SETTING_FLOAT_ARRAY) store_value(&settings, info, info.default_value);
        }
    });
    *out = settings;
    return Error();
}

Error resolve_settings(const obscura_settings& in, obscura_settings* out) {
    if (in.struct_size != sizeof(obscura_settings)) {
        return Error::make(OBSCURA_STATUS_INVALID_STRUCT_SIZE, "obscura_settings.struct_size is %u; expected %u",
                           in.struct_size, unsigned(sizeof(obscura_settings)));
    }
    obscura_method method = resolve_method_value(stored_method(in));
    if (method == OBSCURA_METHOD_COUNT_) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "obscura_settings.method = %d is not an obscura_method",
                           int(stored_method(in)));
    }
    if ((in.flags & ~uint32_t(OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE)) != 0) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "obscura_settings.flags = 0x%x has unknown bits",
                           unsigned(in.flags));
    }
    // resolution.scale is declared as the C enum obscura_resolution (its metadata row an ENUM like those of the int32_t
    // fields with named values): a value the enum does not have is INVALID_ENUM, as for every C enum field.
    const int32_t scale = stored_enum(in.resolution.scale);
    if (scale < OBSCURA_RESOLUTION_DEFAULT || scale > OBSCURA_RESOLUTION_QUARTER) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "obscura_settings.resolution.scale = %d is not an obscura_resolution",
                           int(scale));
    }
    const bool zero_is_value = (in.flags & OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE) != 0;
    obscura_settings resolved = in;
    resolved.method = method;
    // Every method's block (and the shared temporal block) is defaulted and validated, so a later method switch
    // cannot surprise.
    Error row_error;
    for_each_table([&](const char* block, const obscura_setting_info* rows, uint32_t count) {
        for (uint32_t i = 0; i < count && !row_error; ++i) {
            const obscura_setting_info& info = rows[i];
            if (info.type == OBSCURA_SETTING_FLOAT_ARRAY) continue;  // the method's derive step checks it
            if (info.type == OBSCURA_SETTING_TOGGLE) {
                int32_t toggle = *field_at<int32_t>(&resolved, info.offset);
                if (toggle < OBSCURA_TOGGLE_DEFAULT || toggle > OBSCURA_TOGGLE_OFF) {
                    row_error = Error::make(OBSCURA_STATUS_INVALID_ENUM, "%s.%s = %d is not an obscura_toggle", block,
                                            info.name, toggle);
                    return;
                }
                if (toggle == OBSCURA_TOGGLE_DEFAULT) {
                    *field_at<int32_t>(&resolved, info.offset) =
                        info.default_value != 0.0 ? OBSCURA_TOGGLE_ON : OBSCURA_TOGGLE_OFF;
                }
                continue;
            }
            double value = stored_value(resolved, info);
            if (value == 0.0 && !(zero_is_value && zero_can_be_value(info))) {
                store_value(&resolved, info, info.default_value);  // derived fields: 0 until the derive step
                continue;
            }
            row_error = check_value(info, block, value);
        }
    });
    if (row_error) return row_error;
    uint32_t method_count = 0;
    const MethodDescriptor* const* methods = method_descriptors(&method_count);
    for (uint32_t m = 0; m < method_count; ++m) {
        Error error = methods[m]->derive(in, &resolved);
        if (error) return error;
    }
    *out = resolved;
    return Error();
}

void derive_for_renderer(bool cpu_renderer, obscura_settings* resolved) {
    uint32_t method_count = 0;
    const MethodDescriptor* const* methods = method_descriptors(&method_count);
    for (uint32_t m = 0; m < method_count; ++m) {
        if (methods[m]->derive_for_renderer) methods[m]->derive_for_renderer(cpu_renderer, resolved);
    }
}

Error reference_settings_for(const obscura_settings& method_settings, obscura_settings* out) {
    obscura_settings resolved;
    Error error = resolve_settings(method_settings, &resolved);
    if (error) return error;
    const MethodDescriptor* row = find_method(resolved.method);
    if (!row->reference_falloff) {  // REFERENCE: its settings are the reference, of one frame at the full size
        *out = resolved;
        out->temporal.enabled = OBSCURA_TOGGLE_OFF;
        out->resolution.scale = OBSCURA_RESOLUTION_FULL;
        return Error();
    }
    obscura_settings reference;
    std::memset(&reference, 0, sizeof reference);
    reference.struct_size = sizeof reference;
    reference.method = OBSCURA_METHOD_REFERENCE;
    row->reference_falloff(resolved, &reference.reference);
    return resolve_settings(reference, out);
}

Error get_setting(const obscura_settings& settings, const char* name, double* value) {
    obscura_method method = resolve_method_value(stored_method(settings));
    if (method == OBSCURA_METHOD_COUNT_) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "settings.method = %d is not an obscura_method",
                           int(stored_method(settings)));
    }
    const obscura_setting_info* info = find_info(method, name);
    if (!info) {
        return Error::make(OBSCURA_STATUS_UNKNOWN_SETTING, "%s has no setting named '%s'", obscura_method_name(method),
                           name);
    }
    if (info->type == OBSCURA_SETTING_FLOAT_ARRAY) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s is an array of %u values: read it through its offset",
                           block_name(method, *info), info->name, unsigned(info->value_count));
    }
    // Reported as it will be used: derived values for derived fields, and what resolve makes of a set value
    // (LSAO rounds segment_steps up to a multiple of 8).
    obscura_settings resolved;
    if (resolve_settings(settings, &resolved).ok()) {
        const double stored = stored_value(resolved, *info);
        *value = info->type == OBSCURA_SETTING_TOGGLE ? (stored > 0.0 ? 1.0 : 0.0) : stored;
        return Error();
    }
    // Settings that do not resolve read as stored, zero fields as their defaults: a derived field left to derive
    // reads 0, "derive" (there is no derived value; obscura_resolve_settings says why). Editors read every row
    // while a user is half way through a change (a table falloff before its table), so this is not an error.
    const double stored = stored_value(settings, *info);
    if (info->type == OBSCURA_SETTING_TOGGLE) {
        *value = stored == 0.0 ? info->default_value : (stored > 0.0 ? 1.0 : 0.0);
    } else {
        const bool literal_zero = (settings.flags & OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE) && zero_can_be_value(*info);
        *value = stored != 0.0 || literal_zero ? stored : info->default_value;
    }
    return Error();
}

Error set_setting(obscura_settings* settings, const char* name, double value, uint32_t host_size) {
    obscura_method method = resolve_method_value(stored_method(*settings));
    if (method == OBSCURA_METHOD_COUNT_) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "settings.method = %d is not an obscura_method",
                           int(stored_method(*settings)));
    }
    const obscura_setting_info* info = find_info(method, name);
    if (!info || !field_fits(*info, host_size)) {
        return Error::make(OBSCURA_STATUS_UNKNOWN_SETTING, "%s has no setting named '%s'%s",
                           obscura_method_name(method), name,
                           info ? " in the caller's (older) obscura_settings" : "");
    }
    if (info->type == OBSCURA_SETTING_FLOAT_ARRAY) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                           "%s.%s is an array of %u values: write it through its offset", block_name(method, *info),
                           info->name, unsigned(info->value_count));
    }
    // Whether the field will hold 0: a float field also turns a tiny double into 0.
    const bool stores_zero = info->type == OBSCURA_SETTING_FLOAT
                                 ? std::fabs(value) <= double(std::numeric_limits<float>::max()) && float(value) == 0.0f
                                 : value == 0.0;
    if (info->type == OBSCURA_SETTING_TOGGLE) {
        if (value != 0.0 && value != 1.0) {
            return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s is a toggle: 0 (off) or 1 (on), not %g",
                               block_name(method, *info), info->name, value);
        }
    } else if (stores_zero && zero_can_be_value(*info)) {
        // A literal 0 where 0 would mean "default": the struct switches to OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE,
        // whose other such fields then hold their defaults explicitly, so they keep meaning what they meant.
        if (!(settings->flags & OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE)) {
            if (host_size <= offsetof(obscura_settings, flags)) {
                return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                                   "%s.%s = 0 needs OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE, which the caller's (older) "
                                   "obscura_settings has no field for",
                                   block_name(method, *info), info->name);
            }
            for_each_table([&](const char*, const obscura_setting_info* rows, uint32_t count) {
                for (uint32_t i = 0; i < count; ++i) {
                    const obscura_setting_info& other = rows[i];
                    if (zero_can_be_value(other) && stored_value(*settings, other) == 0.0) {
                        store_value(settings, other, other.default_value);
                    }
                }
            });
            settings->flags |= OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE;
        }
    } else if (!(value == 0.0 && (info->min_value > 0.0 || is_derived(*info)))) {
        // 0 means "default" (or "derive") for fields whose range excludes it.
        Error error = check_value(*info, block_name(method, *info), value);
        if (error) return error;
    }
    store_value(settings, *info, value);
    return Error();
}

}  // namespace obscura
