// How many EGL devices this machine offers (EGL_EXT_device_enumeration): what `lghd --gpus all`
// starts a render worker on each of. A software-only machine lists Mesa's one software device.
#pragma once

namespace lgh {

// Throws lgh::Error(Unavailable) when libEGL or its device enumeration is missing.
int eglDeviceCount();

}  // namespace lgh
