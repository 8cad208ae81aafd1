// Sanitizer defaults of binaries that open a Vulkan device (linked only when VSGL_SANITIZE is
// on). The Vulkan loader, lavapipe and the validation layer keep allocations alive at exit from
// modules they dlclose before LeakSanitizer reports, so the reports cannot even be symbolised;
// leak checking is off for these binaries while AddressSanitizer and UBSan stay on. Our own
// allocations are leak-checked by unit_tests.
extern "C" const char* __asan_default_options() {
  return "detect_leaks=0";
}
