/*
 * pcl_ncut_seg tools: the build a program was compiled from, so that every figure it writes can
 * name the binary that made it (not the source tree it happens to sit in when run).
 */
#pragma once

namespace pcl_ncut_seg {

/** \brief `git describe --always --dirty` of the source tree when this binary was built ("-dirty":
 * with uncommitted changes), or "unknown" outside a git checkout. Written by
 * cmake/build_info.cmake at every build. */
const char* buildDescription();

/** \brief The project's version, "0.1.0". */
const char* projectVersion();

} // namespace pcl_ncut_seg
