// Every error coxmesh throws, and its assertions.
//
// Errors: bad input is an exception with one clear sentence (front ends print it as one line);
// a broken invariant of the library itself is a bug, caught by an assertion.
//
// Assertions come in three tiers (after geogram):
//   COXMESH_ASSERT           always on: cheap checks of preconditions whose violation would corrupt
//                            memory or results silently;
//   COXMESH_DEBUG_ASSERT     on in debug builds (without NDEBUG) and with COXMESH_PARANOID;
//   COXMESH_PARANOID_ASSERT  only with COXMESH_PARANOID (the sanitizer build in CI): checks that cost
//                            as much as the work they guard.
// A failed assertion prints the condition and its place and aborts.
#pragma once

#include <stdexcept>

namespace coxmesh {

/// Invalid input: dimensions, NaN/Inf, malformed text or files, overflow, singular matrices.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A seed cannot start the tracing (no simplex near it meets M̂, or it lies outside the domain):
/// never a silently empty result.
struct SeedError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A function returned NaN or ±Inf at a point; the message names the point.
struct EvaluationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void assertion_failed(const char* condition, const char* file, int line);

}  // namespace coxmesh

#define COXMESH_ASSERT(condition) \
  ((condition) ? static_cast<void>(0) : ::coxmesh::assertion_failed(#condition, __FILE__, __LINE__))

#if !defined(NDEBUG) || defined(COXMESH_PARANOID)
#define COXMESH_DEBUG_ASSERT(condition) COXMESH_ASSERT(condition)
#else
#define COXMESH_DEBUG_ASSERT(condition) static_cast<void>(0)
#endif

#if defined(COXMESH_PARANOID)
#define COXMESH_PARANOID_ASSERT(condition) COXMESH_ASSERT(condition)
#else
#define COXMESH_PARANOID_ASSERT(condition) static_cast<void>(0)
#endif
