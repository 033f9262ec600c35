// Assembler directives around a file embedded with .incbin (app/render/shader_sources.cpp,
// app/plot/font.cpp): open a read-only data section for `symbol`, give the symbol its size,
// and leave the section again.
//
// ELF (the desktop build): one .rodata section pushed and popped; symbols need no size.
// WebAssembly (the web build, docs/web.md): the wasm assembler has no .pushsection, and
// every data symbol must live in its own named data section and carry a size.
#pragma once

#if defined(__wasm__)
#define INVFREE_RODATA_OPEN(symbol) ".section .rodata." #symbol ",\"\",@\n"
#define INVFREE_RODATA_SIZE(symbol) ".size " #symbol ", . - " #symbol "\n"
#define INVFREE_RODATA_CLOSE ".text\n"
#else
#define INVFREE_RODATA_OPEN(symbol) ".pushsection .rodata\n"
#define INVFREE_RODATA_SIZE(symbol) ""
#define INVFREE_RODATA_CLOSE ".popsection\n"
#endif
