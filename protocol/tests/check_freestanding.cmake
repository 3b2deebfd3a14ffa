# cmake -DNM=<nm> -DELF=<image> -P check_freestanding.cmake
# Fails when the image links the heap, C++ exceptions, RTTI or abort().
execute_process(COMMAND ${NM} --demangle ${ELF} OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NM} ${ELF} failed")
endif()
string(REGEX MATCHALL "[^\n]*( malloc| free| _malloc_r| operator new| operator delete| __cxa_[a-z_]*| _Unwind_[A-Za-z_]*| typeinfo [^\n]*| abort)\n" found "${symbols}")
if(found)
  message(FATAL_ERROR "${ELF} is not freestanding; it links:\n${found}")
endif()
