" Vim syntax file
" Language:	CSF physics scenes (csf(5))
" Files:	*.csf
" A unit is recognised only right after a number or a closing parenthesis,
" as the compiler does: '2 m' is two metres, '2 * m' twice the variable m.

if exists("b:current_syntax")
  finish
endif

let s:cpo_save = &cpo
set cpo&vim

syn case match

" plain names first: every later match starting at the same place wins
syn match   csfName		"\h\w*"

" comments, strings, the using directive
syn keyword csfTodo		contained TODO FIXME XXX NOTE
syn match   csfComment		"#.*$" contains=csfTodo,@Spell
syn match   csfString		+"[^"\n]*"+
syn match   csfUsing		"^\s*using\>" nextgroup=csfUsingPath skipwhite
syn match   csfUsingPath	"[^#]*[^# \t]" contained

" statements
syn match   csfObject		"^\s*object\>" nextgroup=csfObjectName skipwhite
syn match   csfObjectName	"\h\w*" contained nextgroup=csfArrayRange skipwhite
syn match   csfArrayRange	"\[[^\]]*\]" contained contains=csfNumber,csfRange,csfName
syn match   csfKind		"\(^\s*object\s\+\h\w*\s*\(\[[^\]]*\]\)\=\s*:\s*\)\@<=\h\w*\ze\s*\(#.*\)\=$"
syn match   csfProperty		"\(^\s*object\s\+\h\w*\s*\(\[[^\]]*\]\)\=\s*:\s*\(vector\s\+\)\=\)\@<=\h\w*\ze\s*="
syn match   csfDef		"^\s*def\>" nextgroup=csfKindName skipwhite
syn match   csfKindName		"\h\w*" contained
syn match   csfGlobal		"^\s*global\>" nextgroup=csfVectorKw,csfGlobalName skipwhite
syn keyword csfVectorKw		vector contained nextgroup=csfGlobalName skipwhite
syn match   csfGlobalName	"\h\w*" contained
syn match   csfVector		"^\s*vector\>"
syn match   csfVector		"\(:\s*\)\@<=vector\>"
syn match   csfRule		"^\s*rule\>" nextgroup=csfAttribute,csfFor skipwhite
syn match   csfAttribute	"\(for\>\)\@!\a\+\ze\s*\(:\|for\>\)" contained nextgroup=csfFor skipwhite
syn match   csfWhen		"^\s*when\>" nextgroup=csfFor skipwhite
syn match   csfFor		"\<for\>" contained nextgroup=csfForList skipwhite
syn match   csfForList		"[^:#]*" contained contains=csfForName,csfNumber,csfBinding
syn match   csfForName		"\h\w*" contained
syn match   csfStop		"^\s*stop\s\+when\>"
syn match   csfAssert		"^\s*assert\>"
syn keyword csfConditional	if elif else
syn match   csfFrom		"\(:\s*\)\@<=from\>"
syn keyword csfAtol		atol

" the start directive
syn match   csfStart		"^\s*inc\>" nextgroup=csfTime skipwhite
syn match   csfTime		"\h\w*" contained
syn keyword csfStartKw		till by watch

" names
syn keyword csfPredefined	t RF
syn keyword csfConstant		g G c e pi
syn match   csfConstant		"π"
syn keyword csfProtected	None True False const scalar start step Pi
syn keyword csfOperatorWord	and or not
syn match   csfBinding		"\$\d\+"
syn match   csfMember		"\(\h\w*\(\[[^\]]*\]\)\=\.\)\@<=\h\w*"
syn match   csfMethod		"\.\s*\zs\(mul\|dot\|cross\|mag\|angle\|unit\|proj\)\>"
syn match   csfComponent	"\.\zs[xyz]\>"
syn match   csfFunction		"\<\(sin\|cos\|tan\|asin\|acos\|atan\|sinh\|cosh\|tanh\|exp\|log\|log10\|sqrt\|abs\|atan2\|min\|max\|floor\|mod\|sph\|cyl\|cart\|contact\|sum\)\ze\s*("
syn match   csfSumFor		"\<for\>\ze\s\+\h\w*\s*)"
syn match   csfRange		"\.\."
syn match   csfDerivative	"\(\w\)\@<='"

" numbers, and the unit literal after a number or a closing parenthesis
syn match   csfNumber		"\%(\.\.\|[^[:alnum:]_.$]\|^\)\@<=\%(\d\+\%(\.\%(\.\)\@!\d*\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=" nextgroup=csfUnit skipwhite
syn match   csfNumber		"\<\%(Inf\|NaN\)\>"
syn match   csfParen		")" nextgroup=csfUnit skipwhite
syn match   csfUnit		"\%(\<\%(and\|or\|not\|for\|if\|elif\|else\|by\|till\|watch\|from\|when\|atol\)\>\)\@!\%(\h\w*\|1\%(\s*\/\)\@=\|([[:alnum:]_*/^ ()-]*)\)\%(\^-\=\d\+\)\=\%(\s*[*/]\s*\%(\h\w*\|([[:alnum:]_*/^ ()-]*)\)\%(\^-\=\d\+\)\=\)*" contained

hi def link csfComment		Comment
hi def link csfTodo		Todo
hi def link csfString		String
hi def link csfUsing		Include
hi def link csfUsingPath	String
hi def link csfFrom		Include
hi def link csfObject		Structure
hi def link csfObjectName	Identifier
hi def link csfKind		Type
hi def link csfKindName		Type
hi def link csfProperty		Identifier
hi def link csfDef		Structure
hi def link csfGlobal		StorageClass
hi def link csfVectorKw		StorageClass
hi def link csfVector		StorageClass
hi def link csfGlobalName	Identifier
hi def link csfRule		Statement
hi def link csfAttribute	Label
hi def link csfWhen		Conditional
hi def link csfFor		Keyword
hi def link csfSumFor		Keyword
hi def link csfForName		Identifier
hi def link csfStop		Statement
hi def link csfAssert		Statement
hi def link csfConditional	Conditional
hi def link csfAtol		Keyword
hi def link csfStart		PreProc
hi def link csfStartKw		PreProc
hi def link csfTime		Special
hi def link csfPredefined	Special
hi def link csfConstant		Constant
hi def link csfProtected	Error
hi def link csfOperatorWord	Operator
hi def link csfBinding		Special
hi def link csfMethod		Function
hi def link csfFunction		Function
hi def link csfComponent	Identifier
hi def link csfMember		Identifier
hi def link csfRange		Operator
hi def link csfDerivative	Operator
hi def link csfNumber		Number
hi def link csfUnit		Type

let b:current_syntax = "csf"

let &cpo = s:cpo_save
unlet s:cpo_save
