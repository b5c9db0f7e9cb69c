" tests/editors/vim_check.vim: run by tests/editors/check.sh (vim -es), with g:expect (a file of
" "FILE LINE COL GROUPS" lines), g:scene (a .csf file) and g:out set: for each, the syntax group at
" that place must be one of GROUPS, and the scene's filetype csf; each miss is a FAIL line in g:out.
let s:fails = []
let s:file = ''
for s:e in readfile(g:expect)
  let [s:f, s:l, s:c, s:want] = split(s:e)
  if s:f !=# s:file
    execute 'silent edit! ' . fnameescape(s:f)
    let s:file = s:f
    " the samples are .sample files: their filetype is set here (ftdetect is tested on a .csf)
    setfiletype csf
  endif
  let s:got = synIDattr(synID(str2nr(s:l), str2nr(s:c), 1), 'name')
  if index(split(s:want, '|'), s:got) < 0
    call add(s:fails, printf('FAIL: vim: %s:%s:%s: %s, expected %s: %s', s:f, s:l, s:c, s:got == '' ? 'no group' : s:got, s:want, getline(str2nr(s:l))))
  endif
endfor
" ftdetect: a .csf file is csf
execute 'silent edit! ' . fnameescape(g:scene)
if &filetype !=# 'csf'
  call add(s:fails, 'FAIL: vim: ' . g:scene . ': filetype is "' . &filetype . '", not csf (ftdetect/csf.vim)')
endif
call writefile(s:fails + ['checked ' . len(readfile(g:expect)) . ' places, ' . len(s:fails) . ' failed'], g:out)
qall!
