// The temporal accumulation's settings (obscura_temporal_settings): one metadata table that every method shares.
// The settings machinery (settings.cpp) walks it after the methods' tables; obscura_get_temporal_setting_infos
// hands it out, and set/get by name find its rows for every method.
#ifndef OBSCURA_TEMPORAL_SETTINGS_H
#define OBSCURA_TEMPORAL_SETTINGS_H

#include "obscura/obscura.h"

namespace obscura {

// The rows (offsets inside obscura_settings), and their count.
const obscura_setting_info* temporal_setting_infos(uint32_t* count);

}  // namespace obscura

#endif  // OBSCURA_TEMPORAL_SETTINGS_H
