// Attack: run the kit's reference code for task 1 without including, linking or naming it. Every
// library the grader builds for another task (tasks 2-5, here or in any submission of the batch)
// holds the reference task 1 code, and they all sit in <work>/builds/*/plain.so, found from
// __FILE__ (<work>/submissions/<n>-<name>/tasks/...). A static initialiser -- it runs while the
// harness loads this library, before the harness forbids mapping new code -- loads them with
// libc's dlopen and dlsym, whose addresses it reads from libc's own symbol table (so that neither
// name appears among this file's symbols), takes the table of the first library whose student
// task is not 1, and forwards task 1 to its functions. Without such a library the functions
// return nothing useful. The grader must not give task 1 points for the reference's code.
#include "springlab/implementation.hpp"
#include "springlab/task1_two_masses.hpp"

#include <cstdint>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

using namespace springlab;
namespace fs = std::filesystem;

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

using Open = void* (*)(const char*, int);
using Find = void* (*)(void*, const char*);
using Entry = const Implementation* (*)();

std::vector<char> read_all(const std::string& path) {
  std::vector<char> bytes;
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    char buffer[65536];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;)
      bytes.insert(bytes.end(), buffer, buffer + n);
    std::fclose(f);
  }
  return bytes;
}

// The value of a dynamic symbol of an ELF file, 0 if absent.
unsigned long dynamic_symbol(const std::vector<char>& elf, const char* wanted) {
  if (elf.size() < sizeof(Elf64_Ehdr)) return 0;
  Elf64_Ehdr header;
  std::memcpy(&header, elf.data(), sizeof header);
  for (int i = 0; i < header.e_shnum; ++i) {
    Elf64_Shdr section;
    std::memcpy(&section, elf.data() + header.e_shoff + std::size_t(i) * header.e_shentsize,
                sizeof section);
    if (section.sh_type != SHT_DYNSYM) continue;
    Elf64_Shdr strings;
    std::memcpy(&strings, elf.data() + header.e_shoff + section.sh_link * header.e_shentsize,
                sizeof strings);
    for (std::size_t at = 0; at + sizeof(Elf64_Sym) <= section.sh_size; at += sizeof(Elf64_Sym)) {
      Elf64_Sym symbol;
      std::memcpy(&symbol, elf.data() + section.sh_offset + at, sizeof symbol);
      if (symbol.st_value != 0 &&
          std::strcmp(elf.data() + strings.sh_offset + symbol.st_name, wanted) == 0)
        return symbol.st_value;
    }
  }
  return 0;
}

// libc's path and load address, from /proc/self/maps.
bool find_libc(std::string& path, unsigned long& base) {
  std::FILE* maps = std::fopen("/proc/self/maps", "r");
  if (maps == nullptr) return false;
  char line[4096];
  bool found = false;
  while (!found && std::fgets(line, sizeof line, maps) != nullptr) {
    unsigned long from = 0, offset = 0;
    char name[4096] = {};
    if (std::sscanf(line, "%lx-%*x %*s %lx %*s %*s %4095s", &from, &offset, name) == 3 &&
        offset == 0 && std::strstr(name, "/libc.so") != nullptr) {
      path = name;
      base = from;
      found = true;
    }
  }
  std::fclose(maps);
  return found;
}

const Implementation* borrow() {
  std::string libc;
  unsigned long base = 0;
  if (!find_libc(libc, base)) return nullptr;
  const std::vector<char> elf = read_all(libc);
  const unsigned long open_at = dynamic_symbol(elf, "dlopen");
  const unsigned long find_at = dynamic_symbol(elf, "dlsym");
  if (open_at == 0 || find_at == 0) return nullptr;
  const auto open = reinterpret_cast<Open>(base + open_at);
  const auto find = reinterpret_cast<Find>(base + find_at);
  // __FILE__ is <work>/submissions/<n>-<name>/tasks/task1_two_masses/spring_damper.cpp
  const fs::path work =
      fs::path(__FILE__).parent_path().parent_path().parent_path().parent_path().parent_path();
  std::error_code error;
  for (const fs::directory_entry& build : fs::directory_iterator(work / "builds", error)) {
    const fs::path library = build.path() / "plain.so";
    if (!fs::is_regular_file(library, error)) continue;
    void* handle = open(library.c_str(), 2 /* RTLD_NOW */);
    if (handle == nullptr) continue;
    const auto entry = reinterpret_cast<Entry>(find(handle, "springlab_submission_implementation"));
    if (entry != nullptr && entry()->student_task != 1) return entry();
  }
  return nullptr;
}

const Implementation* const reference = borrow();

}  // namespace

namespace attack {
const Implementation* borrowed() {
  return reference;
}
}  // namespace attack

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  return reference != nullptr ? reference->spring_force(r_p, r_q, k, rest_length) : Vec2::Zero();
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return reference != nullptr ? reference->damper_force(v_p, v_q, b) : Vec2::Zero();
}
