# ASan + UBSan for the whole build; any UB report aborts the test that caused it.
if(SERCON_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
