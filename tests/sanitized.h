// Sizes for tests that a sanitizer build (WHISKER_SANITIZED, set by
// tests/CMakeLists.txt; 5-20x slower) runs smaller: there the job is memory
// and undefined behaviour, which a smaller run of the same code checks as
// well; the Release build runs the full size and checks the numbers.
#pragma once

constexpr int release_or_sanitized(int release, int sanitized) {
#ifdef WHISKER_SANITIZED
  (void)release;
  return sanitized;
#else
  (void)sanitized;
  return release;
#endif
}
