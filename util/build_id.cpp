#include "util/build_id.h"

#include <elf.h>
#include <link.h>

#include <cstdint>
#include <cstdio>
#include <cstring>

namespace sdfbench {
namespace {

std::string read_build_id() {
  std::string id;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) -> int {
        // The first object dl_iterate_phdr reports is the main program.
        for (ElfW(Half) i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& ph = info->dlpi_phdr[i];
          if (ph.p_type != PT_NOTE) continue;
          const auto* p = reinterpret_cast<const unsigned char*>(info->dlpi_addr + ph.p_vaddr);
          const unsigned char* end = p + ph.p_memsz;
          const uint32_t pad = ph.p_align == 8 ? 7u : 3u;  // a segment of 8-aligned notes pads to 8
          while (p + sizeof(ElfW(Nhdr)) <= end) {
            ElfW(Nhdr) note;
            std::memcpy(&note, p, sizeof note);
            const unsigned char* name = p + sizeof note;
            const unsigned char* desc = name + ((note.n_namesz + pad) & ~pad);
            if (desc + note.n_descsz > end) break;
            if (note.n_type == NT_GNU_BUILD_ID && note.n_namesz == 4 && std::memcmp(name, "GNU", 4) == 0) {
              auto& hex = *static_cast<std::string*>(out);
              for (uint32_t k = 0; k < note.n_descsz; ++k) {
                char byte[3];
                std::snprintf(byte, sizeof byte, "%02x", desc[k]);
                hex += byte;
              }
              return 1;
            }
            p = desc + ((note.n_descsz + pad) & ~pad);
          }
        }
        return 1;  // only the main program
      },
      &id);
  return id;
}

}  // namespace

const std::string& executable_build_id() {
  static const std::string id = read_build_id();
  return id;
}

}  // namespace sdfbench
