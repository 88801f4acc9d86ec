/* Linked into every test executable of a sanitizer build (tests/CMakeLists.txt): dlclose() keeps the library
   loaded. Mesa's EGL and DRI drivers are unloaded by eglTerminate when a test destroys its last context (the
   context-loss, host-loader and GL-version tests do); a block the driver still points at from its globals then
   looks leaked, and LeakSanitizer, which can no longer name the unloaded module, reports it as
   "<unknown module>" where lsan.supp cannot match it (Mesa 22.3.6 on Debian 12: 128 bytes from realloc). Kept
   loaded, the driver's blocks stay reachable or attributed to their module, and every leak of the SDK, the
   samples and the tests is still reported. The executable's definition interposes libc's for every library. */
int dlclose(void* handle);

int dlclose(void* handle) {
    (void)handle;
    return 0;
}
