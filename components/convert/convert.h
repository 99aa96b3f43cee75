#pragma once

// Every IDL family's conversion, for the generic DDS adapter (runtime/component_io.h).
#include "convert/base_convert.h"
#include "convert/localization_convert.h"
#include "convert/mission_convert.h"
#include "convert/perception_convert.h"
#include "convert/sensors_convert.h"
#include "convert/system_convert.h"
