// AddressSanitizer's defaults for the executables of a build with STICKREP_SANITIZE
// containing address (the gtests and the programs): Fast DDS 2.9 deletes its RTPSWriter through a base of another size (Debian's
// libfastrtps, not our code: ~RTPSWriter -> operator delete(void*, size_t)), which ASan
// reports as new-delete-type-mismatch whenever a DataWriter is deleted. Every other check
// stays on; ASAN_OPTIONS set by hand still override these.
extern "C" const char* __asan_default_options() { return "new_delete_type_mismatch=0"; }
