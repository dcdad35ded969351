// Compiled only to carry the precompiled headers of cmake/Lc2wfPch.cmake, which other targets reuse.
