" tests/editors/vim_indent.vim: run by tests/editors/check.sh (vim -es) with g:sample and g:out:
" the sample's lines stripped of their indentation and indented again by = (CsfIndent) must be
" the sample; the options of ftplugin/csf.vim. FAIL lines in g:out.
let s:fails = []
execute 'silent edit! ' . fnameescape(g:sample)
setfiletype csf
let s:want = getline(1, '$')
silent %s/^\s\+//e
normal! gg=G
let s:got = getline(1, '$')
for s:i in range(len(s:want))
  if s:got[s:i] !=# s:want[s:i]
    call add(s:fails, printf('FAIL: vim: indentation of line %d: "%s", expected "%s"', s:i + 1, s:got[s:i], s:want[s:i]))
  endif
endfor
if !&expandtab || &shiftwidth != 4 || &commentstring !=# '# %s' || &comments !~# '#'
  call add(s:fails, printf('FAIL: vim: ftplugin: expandtab %d shiftwidth %d commentstring "%s" comments "%s"', &expandtab, &shiftwidth, &commentstring, &comments))
endif
" a tab typed in the indentation becomes spaces
execute "normal! Go\<Tab>x = 1\<Esc>"
if getline('$') !=# '    x = 1'
  call add(s:fails, 'FAIL: vim: a tab typed at the start of a line: "' . getline('$') . '"')
endif
call writefile(s:fails + ['indentation: ' . len(s:fails) . ' failed'], g:out)
qall!
