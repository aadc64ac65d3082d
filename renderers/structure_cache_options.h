#pragma once
// The run's stored-structure cache settings (--cache FILE, --on-bad-cache), as every backend
// receives them in BackendOptions; the backends that store a structure read them (the SDF cache,
// renderers/sdf/sdf_cache.h), the others never do.
#include <string>

namespace sdfbench {

enum class BadCachePolicy {
  Refuse,   // an invalid or stale cache is an error (default: never silently pay a rebuild)
  Rebuild,  // rebuild and overwrite it
};

struct CacheOptions {
  std::string path;  // empty: no cache, always build in memory
  BadCachePolicy on_bad = BadCachePolicy::Refuse;
};

}  // namespace sdfbench
