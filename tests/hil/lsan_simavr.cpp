// libsimavr 1.6 never frees the IRQ tables it allocates per chip (avr_terminate leaves them):
// a leak inside the emulator, not in armctl. Tell LeakSanitizer so the ASan build stays clean
// for everything else.
extern "C" const char* __lsan_default_suppressions() { return "leak:libsimavr\n"; }
