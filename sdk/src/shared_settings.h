// The settings every method shares (obscura_temporal_settings, obscura_resolution_settings): one metadata table.
// The settings machinery (settings.cpp) walks it after the methods' tables; obscura_get_shared_setting_infos hands
// it out, and set/get by name find its rows for every method.
#ifndef OBSCURA_SHARED_SETTINGS_H
#define OBSCURA_SHARED_SETTINGS_H

#include "obscura/obscura.h"

namespace obscura {

// The rows (offsets inside obscura_settings), and their count.
const obscura_setting_info* shared_setting_infos(uint32_t* count);

}  // namespace obscura

#endif  // OBSCURA_SHARED_SETTINGS_H
