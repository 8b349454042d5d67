# Run after lcm-gen (cmake -DDIR=<cpp-hpath> -P LcmDecoderBounds.cmake).
#
# lcm-gen 1.3's C++ decoders resize each variable-length array to the count read
# from the wire before they check that the buffer holds that many elements, so a
# 60-byte message with a corrupt count makes a service allocate and zero
# gigabytes (or throw from std::vector), and they pass a zero or negative string
# length on to std::string. Every array element takes at least one byte on the
# wire, so a count above the bytes left cannot decode: the inserted checks return
# -1 (decode failed) before the allocation. Valid messages decode unchanged.
file(GLOB headers ${DIR}/nerv/*.hpp)
foreach(header ${headers})
  file(READ ${header} text)
  string(REGEX MATCHALL "\\.resize\\(" resizes "${text}")
  string(REGEX REPLACE
    "\n( *)this->([A-Za-z0-9_]+)\\.resize\\(this->([A-Za-z0-9_]+)\\);"
    "\n\\1if(this->\\3 < 0 || this->\\3 > maxlen - pos) return -1;  // LcmDecoderBounds: count\n\\1this->\\2.resize(this->\\3);"
    text "${text}")
  string(REGEX REPLACE
    "if\\((__[A-Za-z0-9_]+) > maxlen - pos\\) return -1;"
    "if(\\1 <= 0 || \\1 > maxlen - pos) return -1;  // LcmDecoderBounds: length"
    text "${text}")
  string(REGEX MATCHALL "LcmDecoderBounds: count" guarded "${text}")
  list(LENGTH resizes n_resizes)
  list(LENGTH guarded n_arrays)
  if(NOT n_arrays EQUAL n_resizes)
    message(FATAL_ERROR "${header}: ${n_resizes} array resizes but ${n_arrays} bounds checks: "
                        "lcm-gen's output changed, update cmake/LcmDecoderBounds.cmake")
  endif()
  file(WRITE ${header} "${text}")
endforeach()
