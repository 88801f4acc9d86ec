#include "settings.h"

#include "host_enum.h"
#include "method_registry.h"

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

const obscura_setting_info* find_info(obscura_method method, const char* name) {
    uint32_t count = 0;
    const obscura_setting_info* infos = setting_infos(method, &count);
    for (uint32_t i = 0; i < count; ++i) {
        if (std::strcmp(infos[i].name, name) == 0) return &infos[i];
    }
    return nullptr;
}

// Stored value of a field as a double, with 0 meaning "default" (toggles: 0 default, 1 on, 2 off).
double stored_value(const obscura_settings& settings, const obscura_setting_info& info) {
    switch (info.type) {
        case OBSCURA_SETTING_FLOAT: return *field_at<float>(&settings, info.offset);
        case OBSCURA_SETTING_INT: return *field_at<int32_t>(&settings, info.offset);
        case OBSCURA_SETTING_TOGGLE: {
            int32_t toggle = *field_at<int32_t>(&settings, info.offset);
            return toggle == OBSCURA_TOGGLE_DEFAULT ? 0.0 : toggle == OBSCURA_TOGGLE_ON ? 1.0 : -1.0;
        }
    }
    return 0.0;
}

Error check_value(const obscura_setting_info& info, obscura_method method, double value) {
    if (!std::isfinite(value)) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s is %g; it must be finite", obscura_method_name(method),
                           info.name, value);
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
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s = %g is outside [%g, %g]%s%s",
                           obscura_method_name(method), info.name, value, info.min_value, info.max_value,
                           info.unit[0] ? " " : "", info.unit);
    }
    if (info.type != OBSCURA_SETTING_FLOAT && value != std::floor(value)) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s = %g must be a whole number",
                           obscura_method_name(method), info.name, value);
    }
    return Error();
}

void store_value(obscura_settings* settings, const obscura_setting_info& info, double value) {
    switch (info.type) {
        case OBSCURA_SETTING_FLOAT: *field_at<float>(settings, info.offset) = float(value); break;
        case OBSCURA_SETTING_INT: *field_at<int32_t>(settings, info.offset) = int32_t(std::lround(value)); break;
        case OBSCURA_SETTING_TOGGLE:
            *field_at<int32_t>(settings, info.offset) = value != 0.0 ? OBSCURA_TOGGLE_ON : OBSCURA_TOGGLE_OFF;
            break;
    }
}

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

obscura_method resolve_method(obscura_method method) { return resolve_method_value(int32_t(method)); }

const obscura_setting_info* setting_infos(obscura_method method, uint32_t* count) {
    const MethodDescriptor* row = find_method(method);
    *count = row ? row->setting_count : 0;
    return row ? row->settings : nullptr;
}

bool is_known_settings_size(uint32_t struct_size) { return struct_size == sizeof(obscura_settings); }

Error resolve_settings(const obscura_settings& in, obscura_settings* out) {
    if (!is_known_settings_size(in.struct_size)) {
        return Error::make(OBSCURA_STATUS_INVALID_STRUCT_SIZE, "obscura_settings.struct_size is %u; expected %u",
                           in.struct_size, unsigned(sizeof(obscura_settings)));
    }
    obscura_method method = resolve_method_value(stored_method(in));
    if (method == OBSCURA_METHOD_COUNT_) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "obscura_settings.method = %d is not an obscura_method",
                           int(stored_method(in)));
    }
    obscura_settings resolved = in;
    resolved.method = method;
    // Every method's block is defaulted and validated, so a later method switch cannot surprise.
    uint32_t method_count = 0;
    const MethodDescriptor* const* methods = method_descriptors(&method_count);
    for (uint32_t m = 0; m < method_count; ++m) {
        const MethodDescriptor& row = *methods[m];
        for (uint32_t i = 0; i < row.setting_count; ++i) {
            const obscura_setting_info& info = row.settings[i];
            if (info.type == OBSCURA_SETTING_TOGGLE) {
                int32_t toggle = *field_at<int32_t>(&resolved, info.offset);
                if (toggle < OBSCURA_TOGGLE_DEFAULT || toggle > OBSCURA_TOGGLE_OFF) {
                    return Error::make(OBSCURA_STATUS_INVALID_ENUM, "%s.%s = %d is not an obscura_toggle", row.name,
                                       info.name, toggle);
                }
                if (toggle == OBSCURA_TOGGLE_DEFAULT) {
                    *field_at<int32_t>(&resolved, info.offset) =
                        info.default_value != 0.0 ? OBSCURA_TOGGLE_ON : OBSCURA_TOGGLE_OFF;
                }
                continue;
            }
            double value = stored_value(resolved, info);
            if (value == 0.0) {
                store_value(&resolved, info, info.default_value);
                continue;
            }
            Error error = check_value(info, row.method, value);
            if (error) return error;
        }
    }
    for (uint32_t m = 0; m < method_count; ++m) {
        Error error = methods[m]->derive(in, &resolved);
        if (error) return error;
    }
    *out = resolved;
    return Error();
}

Error reference_settings_for(const obscura_settings& method_settings, obscura_settings* out) {
    obscura_settings resolved;
    Error error = resolve_settings(method_settings, &resolved);
    if (error) return error;
    const MethodDescriptor* row = find_method(resolved.method);
    if (!row->reference_falloff) {  // REFERENCE: its settings are the reference
        *out = resolved;
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
    double stored = stored_value(settings, *info);
    if (info->type == OBSCURA_SETTING_TOGGLE) {
        *value = stored == 0.0 ? info->default_value : (stored > 0.0 ? 1.0 : 0.0);
    } else {
        // Reported as it will be used: derived defaults for zero fields, and what resolve makes of a set
        // value (LSAO rounds segment_steps up to a multiple of 8). Settings that do not resolve read as stored.
        obscura_settings resolved;
        if (resolve_settings(settings, &resolved).ok()) stored = stored_value(resolved, *info);
        *value = stored != 0.0 ? stored : info->default_value;
    }
    return Error();
}

Error set_setting(obscura_settings* settings, const char* name, double value) {
    obscura_method method = resolve_method_value(stored_method(*settings));
    if (method == OBSCURA_METHOD_COUNT_) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "settings.method = %d is not an obscura_method",
                           int(stored_method(*settings)));
    }
    const obscura_setting_info* info = find_info(method, name);
    if (!info) {
        return Error::make(OBSCURA_STATUS_UNKNOWN_SETTING, "%s has no setting named '%s'", obscura_method_name(method),
                           name);
    }
    if (info->type == OBSCURA_SETTING_TOGGLE) {
        if (value != 0.0 && value != 1.0) {
            return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s is a toggle: 0 (off) or 1 (on), not %g",
                               obscura_method_name(method), info->name, value);
        }
    } else if (!(value == 0.0 && info->min_value > 0.0)) {
        // 0 always means "default" for fields whose range excludes it.
        Error error = check_value(*info, method, value);
        if (error) return error;
    }
    store_value(settings, *info, value);
    return Error();
}

}  // namespace obscura
