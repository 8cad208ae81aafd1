// Sanitizer defaults of unit_tests (linked only when VSGL_SANITIZE is on). Leak checking stays
// on; the one leak inside a third-party library is suppressed here with its reason:
// OpenImageIO 2.4's PNG reader leaks its read-callback state when libpng aborts on a truncated
// file (PNGInput::PngReadCallback). Frame-pointer unwinding stops inside libstdc++ and would
// hide that frame from the suppression, hence the slow unwinder.
extern "C" const char* __asan_default_options() {
  return "fast_unwind_on_malloc=0";
}
extern "C" const char* __lsan_default_suppressions() {
  return "leak:PNGInput::PngReadCallback\n";
}
