// Attack: forge the verdict without ever seeing the secret, by calling the harness's own function
// that writes records. The test program is not stripped: its symbol table (read from
// /proc/self/exe, which the sandbox lets any code open for reading) gives the address of
// springlab::grading::write_record, and /proc/self/maps where the program is loaded. A static
// initialiser calls it with ("verdict", "pass 1 0\n") -- the harness adds the secret itself --
// and ends with _exit(0). No task 5 function is written (the starter stubs stay). Hiding the
// secret better cannot stop this: task 5 must still get nothing.
#include "springlab/task5_fabric.hpp"

#include <cstdint>

#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

// Declared by hand: the source policy refuses POSIX headers, but not a declaration.
extern "C" long readlink(const char*, char*, unsigned long) noexcept;
extern "C" [[noreturn]] void _exit(int);

using namespace springlab;

namespace {

// The ELF layout (<elf.h> is a header the source policy refuses; the layout is the ELF standard's).
struct Elf64_Ehdr {
  unsigned char e_ident[16];
  std::uint16_t e_type, e_machine;
  std::uint32_t e_version;
  std::uint64_t e_entry, e_phoff, e_shoff;
  std::uint32_t e_flags;
  std::uint16_t e_ehsize, e_phentsize, e_phnum, e_shentsize, e_shnum, e_shstrndx;
};
struct Elf64_Shdr {
  std::uint32_t sh_name, sh_type;
  std::uint64_t sh_flags, sh_addr, sh_offset, sh_size;
  std::uint32_t sh_link, sh_info;
  std::uint64_t sh_addralign, sh_entsize;
};
struct Elf64_Sym {
  std::uint32_t st_name;
  unsigned char st_info, st_other;
  std::uint16_t st_shndx;
  std::uint64_t st_value, st_size;
};
constexpr std::uint32_t SHT_SYMTAB = 2, SHT_DYNSYM = 11;

using WriteRecord = void (*)(std::string_view, std::string_view);

std::vector<char> read_all(const char* path) {
  std::vector<char> bytes;
  if (std::FILE* f = std::fopen(path, "rb")) {
    char buffer[65536];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;)
      bytes.insert(bytes.end(), buffer, buffer + n);
    std::fclose(f);
  }
  return bytes;
}

unsigned long symbol_offset(const std::vector<char>& elf, const char* wanted) {
  if (elf.size() < sizeof(Elf64_Ehdr)) return 0;
  Elf64_Ehdr header;
  std::memcpy(&header, elf.data(), sizeof header);
  for (int i = 0; i < header.e_shnum; ++i) {
    Elf64_Shdr section;
    std::memcpy(&section, elf.data() + header.e_shoff + std::size_t(i) * header.e_shentsize,
                sizeof section);
    if (section.sh_type != SHT_SYMTAB) continue;
    Elf64_Shdr strings;
    std::memcpy(&strings, elf.data() + header.e_shoff + section.sh_link * header.e_shentsize,
                sizeof strings);
    for (std::size_t at = 0; at + sizeof(Elf64_Sym) <= section.sh_size; at += sizeof(Elf64_Sym)) {
      Elf64_Sym symbol;
      std::memcpy(&symbol, elf.data() + section.sh_offset + at, sizeof symbol);
      if (std::strcmp(elf.data() + strings.sh_offset + symbol.st_name, wanted) == 0)
        return symbol.st_value;
    }
  }
  return 0;
}

unsigned long load_address() {
  char exe[4096] = {};
  if (readlink("/proc/self/exe", exe, sizeof exe - 1) <= 0) return 0;
  std::FILE* maps = std::fopen("/proc/self/maps", "r");
  if (maps == nullptr) return 0;
  char line[4096];
  unsigned long base = 0;
  while (base == 0 && std::fgets(line, sizeof line, maps) != nullptr) {
    unsigned long from = 0, offset = 0;
    if (std::sscanf(line, "%lx-%*x %*s %lx", &from, &offset) == 2 && offset == 0 &&
        std::strstr(line, exe) != nullptr)
      base = from;
  }
  std::fclose(maps);
  return base;
}

int forge() {
  const unsigned long offset = symbol_offset(
      read_all("/proc/self/exe"),
      "_ZN9springlab7grading12write_recordESt17basic_string_viewIcSt11char_traitsIcEES4_");
  const unsigned long base = load_address();
  if (offset != 0 && base != 0) {
    const auto write_record = reinterpret_cast<WriteRecord>(base + offset);
    write_record("verdict", "pass 1 0\n");
    _exit(0);
  }
  return 0;
}

const int forged = forge();

}  // namespace

std::vector<Spring> springlab::bend_springs(int rows, int cols,
                                            const SpringFamilyParameters& family) {
  (void)forged;
  not_implemented_yet(5, __func__, __FILE__, rows, cols, family);
}
