" Vim filetype plugin
" Language:	CSF physics scenes (csf(5))
" Comments start with '#'; indentation is spaces only (a tab in the
" indentation is an error); a line ending in ':' (def, a conditional rule,
" if, elif, else, when) opens a block indented one level deeper, elif and
" else go back to the level of their if (the nearest one above), and a
" statement (object, rule, inc, ...) starts at the margin.

if exists("b:did_ftplugin")
  finish
endif
let b:did_ftplugin = 1

setlocal comments=:# commentstring=#\ %s
setlocal expandtab shiftwidth=4 softtabstop=4 tabstop=8
setlocal formatoptions-=t formatoptions+=croql
setlocal indentexpr=CsfIndent(v:lnum) indentkeys=!^F,o,O,0=elif,0=else
setlocal autoindent nolisp nosmartindent

let b:undo_ftplugin = "setlocal comments< commentstring< expandtab< shiftwidth< softtabstop< tabstop<"
      \ . " formatoptions< indentexpr< indentkeys< autoindent< lisp< smartindent<"

if exists("*CsfIndent")
  finish
endif

" The line without its comment and trailing blanks.
function! s:Code(lnum) abort
  return substitute(getline(a:lnum), '\s*#.*$\|\s\+$', '', '')
endfunction

function! CsfIndent(lnum) abort
  let prev = prevnonblank(a:lnum - 1)
  while prev > 0 && s:Code(prev) =~ '^\s*$'
    let prev = prevnonblank(prev - 1)
  endwhile
  if prev == 0
    return 0
  endif
  let ind = indent(prev)
  let line = getline(a:lnum)
  " a statement (object, rule, def, when, ...) is never inside a block
  if line =~ '^\s*\(object\|rule\|def\|global\|using\|when\|assert\|stop\|vector\|inc\)\>'
    return 0
  endif
  " elif and else: at the indentation of the nearest if, elif or rule/when opener above, shallower
  if line =~ '^\s*\(elif\>\|else\s*:\)'
    let l = prev
    while l > 0
      let code = s:Code(l)
      if indent(l) <= ind && code =~ '^\s*\(rule\>.*\<if\>\|if\>\|elif\>\)'
        return indent(l)
      endif
      let l = prevnonblank(l - 1)
    endwhile
    return ind
  endif
  " a line ending in ':' opens a block
  if s:Code(prev) =~ ':$'
    return ind + shiftwidth()
  endif
  return ind
endfunction
