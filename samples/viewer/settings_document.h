// Settings documents of the viewer: save and load an obscura_settings as JSON, and copy it as C.
// Everything is driven by the SDK's settings metadata (obscura_get_setting_infos, obscura_get_setting,
// obscura_set_setting), so a setting added to the SDK appears here with no change.
//
//     std::string json = settings_to_json(settings);        // {"format": "obscura-settings", "version": 2,
//                                                           //  "method": "hbao", "settings": {"radius": 1.5, ...}}
//     obscura_settings loaded = settings_from_json(json);   // SettingsDocumentError with a readable message
//     std::string c = settings_to_c(settings);              // obscura_default_settings(...) + changed fields
//
// Documents hold the editable form (obscura_default_settings): every setting in metadata order, floats in the
// shortest form that reads back to the same float, toggles as "on"/"off", enums by their value names
// ("falloff": "exponential"), the falloff tables of REFERENCE and FFAO as arrays of 16 numbers, and derived
// settings as 0 ("derive": decay rates, LSAO's K, D_S and D_L, SAO's turns, FFAO's K) unless set, so a loaded
// document derives them again from the settings it holds. Version 1 documents (the effective values: derived
// ones written out, enums as numbers, no tables) still load; their derived values that are what the settings
// derive load as "derive". settings_from_json checks each value against its metadata range, then the settings as
// a whole (obscura_resolve_settings: e.g. FFAO's sectors with saao, the table falloff's table), as the method-spec
// parser checks a --method spec.
#ifndef OBSCURA_VIEWER_SETTINGS_DOCUMENT_H
#define OBSCURA_VIEWER_SETTINGS_DOCUMENT_H

#include <stdexcept>
#include <string>
#include <string_view>

#include "obscura/obscura.h"

namespace obscura::viewer {

// The "format" and the highest "version" of the documents written and read here.
inline constexpr const char* kSettingsFormat = "obscura-settings";
inline constexpr int kSettingsVersion = 2;

// A document that cannot be loaded (or settings that cannot be written); what() says why, naming the key.
class SettingsDocumentError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The JSON document of `settings`: every setting of settings.method (DEFAULT: HBAO) in metadata order.
// Throws SettingsDocumentError if the method is not an obscura_method.
std::string settings_to_json(const obscura_settings& settings);

// Parses a document written by settings_to_json (or by hand): starts from obscura_default_settings of its
// "method" and applies each key of "settings" through obscura_set_setting (arrays through their offset);
// missing keys keep their default. "format" and "version" are checked when present. Throws
// SettingsDocumentError: malformed JSON, a missing or unknown method, an unknown key, a value of the wrong type
// or outside its range, a toggle other than "on"/"off"/true/false, an enum value that is neither one of its
// names nor one of its numbers, an array of the wrong length, settings that obscura_resolve_settings refuses
// (with its reason: obscura_get_last_error(NULL)). 0 is accepted where it is a value of the field's range, and in
// derived fields ("derive"); where the range excludes it (radius, intensity, falloff) it is out of range, except
// in version 1 documents, which were read with such a 0 as the field's default.
obscura_settings settings_from_json(std::string_view text);

// The value of `info` that renders with `context` use: obscura_resolve_settings with the context (a derived field's
// derived value; LSAO's segment_steps, which depends on the renderer, as the context's renders settle it), read
// with obscura_get_setting. Settings that do not resolve read as stored (a derived field left 0 reads 0). `context`
// may be NULL: the context-free value. Throws SettingsDocumentError if the read fails.
double effective_setting_value(obscura_context* context, const obscura_settings& settings,
                               const obscura_setting_info& info);

// The panel's "derive" box of a derived setting: ticked, the field goes back to 0, "derive"; unticked, it is set
// to the value renders with `context` use now (effective_setting_value), so that nothing moves and the field stays
// set. False when nothing was stored (not a derived field, refused, or no derived value to keep: settings that do
// not resolve).
bool set_derive(obscura_context* context, obscura_settings& settings, const obscura_setting_info& info, bool derive);

// C that rebuilds `settings`: obscura_default_settings(OBSCURA_METHOD_X, &settings) followed by one assignment
// per setting that differs from the method's default, one statement per line: enums by number with their
// name in a comment, derived fields only where set, an array (all of its elements) where any differs.
// Throws SettingsDocumentError if the method is not an obscura_method.
std::string settings_to_c(const obscura_settings& settings);

// The method whose obscura_method_name() is `name` ("hbao", "sao" ...); false when there is none.
bool method_from_name(std::string_view name, obscura_method* method);

// "hbao, sao, lsao, ffao, reference": the names of every method, for messages.
std::string method_names();

// Writes `text` to `path` (binary, replacing the file); on failure returns false and sets *error (if given).
bool write_text_file(const std::string& path, std::string_view text, std::string* error);

// Reads the whole file at `path` into *text; on failure returns false and sets *error (if given).
bool read_text_file(const std::string& path, std::string* text, std::string* error);

}  // namespace obscura::viewer

#endif  // OBSCURA_VIEWER_SETTINGS_DOCUMENT_H
