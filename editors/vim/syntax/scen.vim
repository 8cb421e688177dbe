" Vim syntax file
" Language:   scen (scenarios for 2D robot motion planning, SPEC.md §2)
" Filenames:  *.scen
"
" The same colouring classes as the VS Code grammar
" (editors/vscode/syntaxes/scen.tmLanguage.json). The lists of planner
" kinds, parameter keys, limit kinds, word values, metrics, aggregates and
" bench keys between the GENERATED lines come from the planner registry and
" the analyser (scripts/regenerate.sh writes them; tests/editors.rs fails
" when they are stale); tests/editors.rs also checks that every keyword of
" the grammar is here.
"
" Families (SPEC 2.8): `param` and `require` are statements; the name that
" `param NAME` declares is a name (scenParamName, as an obstacle's or a
" plan's); a param used in an expression is left uncoloured, like a plan
" reference (scenParamRef in `param`, `require` and `expect`; in world,
" robot and plan positions, where a word may also be a key, a word value or
" a name, a plain word). VS Code scopes them `entity.name.param.scen` and
" `variable.other.param.scen` (`variable.other.word.scen` where a plain
" word). Distributions and functions (`uniform`, `normal`, `int`, `choice`,
" `min`, `sqrt`, ...) are functions like the aggregates; `scatter`, `in`
" and `gap` are world keywords like `bounds`; `+ - * /` are operators, and
" the unit after `(EXPR)` a unit.

if exists('b:current_syntax')
  finish
endif
let s:cpo_save = &cpo
set cpo&vim

syn case match
syn iskeyword @,48-57,_

" ------------------------------------------------ stray text, punctuation
" Defined first: every later item that starts at the same place wins.
syn match   scenStray /\S/
syn match   scenPunct /[()[\],]/
syn match   scenOtherWord /\<\h\w*/
" Arithmetic in number positions (`gap_x - gap_w / 2`); a number's own sign
" (`-1`), defined later, wins.
syn match   scenCalcOperator /[-+*\/]/

" ------------------------------------------------------------- comments
syn keyword scenTodo contained TODO FIXME XXX NOTE
syn match   scenComment /#.*$/ contains=scenTodo,@Spell

" -------------------------------------------------------------- strings
" A string ends at the end of its line; `\"` and `\\` are its escapes.
syn match   scenUnterminated /"\%([^"\\]\|\\.\)*\\\=$/
syn region  scenString start=/"/ skip=/\\./ end=/"/ oneline contains=scenEscape,scenBadEscape
syn match   scenBadEscape contained /\\./
syn match   scenEscape contained /\\["\\]/

" -------------------------------------------------------------- numbers
" `12`, `-3.5`, `1e-3`, `.5`, and with a unit: `90deg`, `1.5rad`, `100%`,
" `500ms`, `2s`. Anything else glued to a number is a malformed number
" (`1.2.3`, `90degx`, `5-3`).
syn match   scenBadNumber /\%([[:alnum:]_.]\)\@1<!-\=\.\=\d[[:alnum:]_.%+-]*/
syn match   scenNumber    /\%([[:alnum:]_.]\)\@1<!-\=\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%([[:alnum:]_.%+-]\)\@!/
syn match   scenAngle     /\%([[:alnum:]_.]\)\@1<!-\=\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%(deg\|rad\)\%([[:alnum:]_.%+-]\)\@!/ contains=scenUnit
syn match   scenPercent   /\%([[:alnum:]_.]\)\@1<!-\=\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=%\%([[:alnum:]_.%+-]\)\@!/ contains=scenUnit
syn match   scenDuration  /\%([[:alnum:]_.]\)\@1<!-\=\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%(ms\|s\)\%([[:alnum:]_.%+-]\)\@!/ contains=scenUnit
syn match   scenUnit contained /\%(deg\|rad\|ms\|s\|%\)\%([[:alnum:]_]\)\@!/
syn cluster scenNumbers contains=scenBadNumber,scenNumber,scenAngle,scenPercent,scenDuration
" In `expect`, `-` is an operator (`2-1`) and a duration is an error:
" metrics are plain numbers.
syn match   scenExprBadNumber contained /\%([[:alnum:]_.]\)\@1<!\.\=\d\%([eE][-+]\=\|[[:alnum:]_.%]\)*/
syn match   scenExprNumber contained    /\%([[:alnum:]_.]\)\@1<!\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%([[:alnum:]_.%]\)\@!/
syn match   scenExprAngle contained     /\%([[:alnum:]_.]\)\@1<!\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%(deg\|rad\)\%([[:alnum:]_.%]\)\@!/ contains=scenUnit
syn match   scenExprPercent contained   /\%([[:alnum:]_.]\)\@1<!\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=%\%([[:alnum:]_.%]\)\@!/ contains=scenUnit
syn match   scenExprDuration contained /\%([[:alnum:]_.]\)\@1<!\%(\d\+\%(\.\d\+\)\=\|\.\d\+\)\%([eE][-+]\=\d\+\)\=\%(ms\|s\)\%([[:alnum:]_.%]\)\@!/
syn cluster scenExprNumbers contains=scenExprBadNumber,scenExprNumber,scenExprAngle,scenExprPercent,scenExprDuration

" ----------------------------------------------------------- statements
" A statement keyword followed by `.` is a plan name (`plan.found`).
syn match   scenStatement /\<\%(scenario\|include\|world\)\>\%(\s*\.\)\@!/
syn match   scenStatement /\<\%(robot\|team\)\>\%(\s*\.\)\@!/ nextgroup=scenName skipwhite
syn match   scenStatement /\<plan\>\%(\s*\.\)\@!/ nextgroup=scenPlanName skipwhite
syn match   scenStatement /\<bench\>\%(\s*\.\)\@!/ nextgroup=scenBenchWord,scenBenchName,scenBenchBlock,scenBenchComment skipwhite skipnl skipempty

" robot NAME SHAPE
syn match   scenName contained /\h\w*/ nextgroup=scenRobotShape skipwhite
" BEGIN GENERATED robot-kinds (scripts/regenerate.sh; do not edit)
syn keyword scenRobotShape contained point disk rect polygon
" END GENERATED robot-kinds
" The clauses after a robot's shape: `steer MODEL RADIUS`, `speed V`; a
" team's `from "FILE.scen" agents N` and the `->` of its agents.
syn keyword scenRobotClause steer speed from agents
" The arrow of a team's agent, `NAME (x, y) -> (x, y)`, in its block.
syn match   scenArrow contained /->/
" plan NAME KIND ROBOT
syn match   scenPlanName contained /\h\w*/ nextgroup=scenPlanner,scenBadPlanner skipwhite
syn match   scenBadPlanner contained /\h\w*/ nextgroup=scenRobotRef skipwhite
" BEGIN GENERATED planners (scripts/regenerate.sh; do not edit)
syn keyword scenPlanner contained astar online roadmap potential coverage rrt nextgroup=scenRobotRef skipwhite
syn keyword scenPlanner contained rrt_connect rrt_star prm prm_star steer hybrid_astar nextgroup=scenRobotRef skipwhite
syn keyword scenPlanner contained bug sipp cbs lacam prioritized nextgroup=scenRobotRef skipwhite
" END GENERATED planners
syn match   scenRobotRef contained /\h\w*/
" bench NAME { ... }: the block (after comments, other words, on later lines
" too) is a bench's, up to the next statement. The name, on the line of
" `bench`, is defined last: it wins over a word.
syn match   scenBenchWord contained /\%(\%(scenario\|include\|world\|robot\|team\|plan\|expect\|bench\|param\|require\)\>\%(\s*\.\)\@!\)\@!\h\w*/ nextgroup=scenBenchWord,scenBenchBlock,scenBenchComment skipwhite skipnl skipempty
syn match   scenBenchName contained /\%(\<bench\s\+\)\@<=\h\w*/ nextgroup=scenBenchWord,scenBenchBlock,scenBenchComment skipwhite skipnl skipempty
syn match   scenBenchComment contained /#.*$/ contains=scenTodo,@Spell nextgroup=scenBenchWord,scenBenchBlock,scenBenchComment skipwhite skipnl skipempty

" Obstacles and robot shapes; an obstacle's name follows its kind
" (`grid cell 1` has none: `cell` is then the grid's option).
syn keyword scenShape rect polygon segment disk grid point nextgroup=scenObstacleName skipwhite
syn match   scenObstacleName contained /\%(\%(cell\|origin\)\s*[-.0-9(\["]\)\@!\h\w*/
" `scatter NAME N disk R | rect W H` up to `in`, which (with `gap`) is a
" world keyword: after `disk` or `rect` come sizes, not a name.
syn region  scenScatter contained matchgroup=scenWorldKeyword start=/\<scatter\>/ end=/\ze\<in\>/ end=/\ze}/
      \ end=/^\ze\%(scenario\|include\|world\|robot\|team\|plan\|expect\|bench\|param\|require\)\>\%(\s*\.\)\@!/
      \ contains=scenStray,scenPunct,scenOtherWord,scenCalcOperator,scenComment,@scenNumbers,scenCalcFunction,scenCalcUnit,scenScatterShape,scenScatterName
syn keyword scenScatterShape contained disk rect
syn match   scenScatterName contained /\%(\<scatter\s\+\)\@<=\h\w*/

" ------------------------------------------------- world and plan blocks
" A statement keyword at the start of a line ends an unclosed block.
syn region  scenBlock matchgroup=scenBrace start=/{/ end=/}/ fold
      \ end=/^\ze\%(scenario\|include\|world\|robot\|team\|plan\|expect\|bench\|param\|require\)\>\%(\s*\.\)\@!/
      \ contains=scenStray,scenPunct,scenOtherWord,scenBlock,scenComment,scenString,scenUnterminated,@scenNumbers,scenShape,scenWorldKeyword,scenParamKey,scenLimitKind,scenWord,scenCalcOperator,scenCalcFunction,scenCalcUnit,scenScatter,scenArrow
" A bench's block: a plan's parameters (the varied keys, `limit`), and
" `plans [NAME, ...]`, `vary KEY [VALUE, ...]`, `runs N`.
syn region  scenBenchBlock contained matchgroup=scenBrace start=/{/ end=/}/ fold
      \ end=/^\ze\%(scenario\|include\|world\|robot\|team\|plan\|expect\|bench\|param\|require\)\>\%(\s*\.\)\@!/
      \ contains=scenStray,scenPunct,scenOtherWord,scenBlock,scenComment,scenString,scenUnterminated,@scenNumbers,scenParamKey,scenLimitKind,scenWord,scenBenchKey,scenCalcOperator,scenCalcFunction,scenCalcUnit
" BEGIN GENERATED bench-keys (scripts/regenerate.sh; do not edit)
syn keyword scenBenchKey contained vary runs worlds
" END GENERATED bench-keys
syn keyword scenBenchKey contained plans nextgroup=scenPlanList skipwhite skipnl skipempty
" The names in `plans [...]` are plans, not words.
syn region  scenPlanList contained matchgroup=scenPunct start=/\[/ end=/\]/
      \ end=/^\ze\%(scenario\|include\|world\|robot\|team\|plan\|expect\|bench\|param\|require\)\>\%(\s*\.\)\@!/
      \ contains=scenStray,scenPunct,scenOtherWord,scenPlanList,scenComment,scenString,scenUnterminated,@scenNumbers
syn keyword scenWorldKeyword contained bounds origin in gap at then stay vanish
syn keyword scenWorldKeyword contained moving nextgroup=scenObstacleName skipwhite
" BEGIN GENERATED parameters (scripts/regenerate.sh; do not edit)
" Parameter keys: the common ones, every planner's, and `drive { ... }`'s.
syn keyword scenParamKey contained start goal seed drive cell sample connect layers cost turn_cost weight heuristic
syn keyword scenParamKey contained rotate strategy sense arc_segments attract repulse influence step tolerance escape
syn keyword scenParamKey contained jump on tool weights range goal_bias sampler stop simplify rewire informed neighbors
syn keyword scenParamKey contained reverse_cost switch_cost analytic variant follow agents refine pibt_runs swap spread
syn keyword scenParamKey contained order dt max_speed max_turn_rate gain turn_gain reach align lookahead speed
syn keyword scenParamKey contained max_curvature
" A key that is a word value too is two matches, not keywords (a keyword would
" win everywhere): the word's, defined later, wins after the keys it follows.
syn match   scenParamKey contained /\<limit\>/
" `limit KIND N`.
syn keyword scenLimitKind contained expansions steps time cells iterations
" Word values.
syn keyword scenWord contained unicycle pure_pursuit center corner auto euclid l1 lattice metric zero yes no backtrack
syn keyword scenWord contained shortcut replan dstar_lite none random_walk sum gaussian bridge first smooth bug1 bug2
syn keyword scenWord contained tangent left right inf all given shortest_first random
syn match   scenWord contained /\<\%(max\|uniform\)\>(\@!/
syn match   scenWord contained /\%(\<stop\s\+\)\@<=limit\>/
" END GENERATED parameters

" --------------------------------------------------------------- expect
" An expression runs until the next statement (not a metric: `p.plan`).
syn region  scenExpect matchgroup=scenStatement start=/\<expect\>\%(\s*\.\)\@!/
      \ end=/\ze\.\@1<!\<\%(scenario\|include\|world\|robot\|team\|plan\|expect\|bench\|param\|require\)\>\%(\s*\.\)\@!/
      \ contains=@scenExpression
" `require CONDITION` (over params): an expression like expect's.
syn region  scenRequire matchgroup=scenStatement start=/\<require\>\%(\s*\.\)\@!/
      \ end=/\ze\.\@1<!\<\%(scenario\|include\|world\|robot\|team\|plan\|expect\|bench\|param\|require\)\>\%(\s*\.\)\@!/
      \ contains=@scenExpression
syn cluster scenExpression contains=scenStray,scenParamRef,scenBadFunction,scenParen,scenComment,scenPlanRef,scenOperator,scenLogical,scenBoolean,scenFunction,@scenExprNumbers
" A bare word is a param (`gap_w >= 1`); a call is an aggregate
" `mean(BENCH.PLAN.METRIC)` or a function `sqrt(x)`, any other is an error.
syn match   scenParamRef contained /\<\h\w*/
syn match   scenBadFunction contained /\<\h\w*\ze(/
" BEGIN GENERATED aggregates (scripts/regenerate.sh; do not edit)
syn match   scenFunction contained /\<\%(mean\|median\|min\|max\|std\|sum\|count\|quantile\|rate\)\ze(/
" END GENERATED aggregates
" BEGIN GENERATED functions (scripts/regenerate.sh; do not edit)
syn match   scenCalcFunction /\<\%(min\|max\|abs\|sqrt\|uniform\|normal\|int\)\ze(/
" END GENERATED functions
syn match   scenParen contained /[(),]/
" PLAN.METRIC, BENCH.PLAN.METRIC and BENCH.PLAN[KEY = VALUE, ...].METRIC,
" one part after the other: after the first `.`, a name followed by `.` or
" `[` is a plan (scenMidRef, scenSelection: defined after the metrics, so
" they win), anything else the metric; after the second `.` or `].`, the
" metric.
syn match   scenPlanRef contained /\<\h\w*\ze\.\h/ nextgroup=scenAccessor
syn match   scenAccessor contained /\./ nextgroup=scenMetric,scenOtherMetric,scenMidRef,scenSelection
syn match   scenLastAccessor contained /\.\ze\h/ nextgroup=scenMetric,scenOtherMetric
syn match   scenOtherMetric contained /\h\w*/
" BEGIN GENERATED metrics (scripts/regenerate.sh; do not edit)
syn match   scenMetric contained /\.\@1<=\%(found\|gave_up\|cost\|length\|turn\|nodes\|expanded\|time_ms\)\>/
syn match   scenMetric contained /\.\@1<=\%(collision_free\|reaches_goal\|clearance\|smoothness\|cells\|free_cells\)\>/
syn match   scenMetric contained /\.\@1<=\%(layers\|generated\|traveled\|steps\|replans\|sensed\|graph_nodes\)\>/
syn match   scenMetric contained /\.\@1<=\%(graph_edges\|minima\|escapes\|coverage\|cells_total\|cells_visited\)\>/
syn match   scenMetric contained /\.\@1<=\%(revisits\|returns_to_start\|uncovered\|tree_edges\|tree_weight\)\>/
syn match   scenMetric contained /\.\@1<=\%(iterations\|graph_states\|collision_checks\|first_iteration\|first_cost\)\>/
syn match   scenMetric contained /\.\@1<=\%(raw_length\|raw_nodes\|simplify_ms\|analytic_tries\|hits\|intervals\)\>/
syn match   scenMetric contained /\.\@1<=\%(high_level\|low_level\|sum_of_loss\|exhausted\|configurations\|planned\)\>/
syn match   scenMetric contained /\.\@1<=\%(drive_time\|drive_max_deviation\|drive_collision_free\)\>/
" END GENERATED metrics
syn match   scenMidRef contained /\h\w*\ze\.\h/ nextgroup=scenLastAccessor
" BENCH.PLAN[...]: the plan's name starts the selection, so that its `[` is
" inside and a key is matched with what precedes it (`[` or `,`) before a
" keyword of the same name could claim it (`[max = 1]`: an unknown key,
" coloured as a key).
syn region  scenSelection contained matchgroup=scenSelectedPlan start=/\h\w*\[\@=/ matchgroup=scenPunct end=/\]/
      \ end=/^\ze\%(scenario\|include\|world\|robot\|team\|plan\|expect\|bench\|param\|require\)\>\%(\s*\.\)\@!/
      \ contains=scenStray,scenPunct,scenOtherWord,scenComment,scenString,scenUnterminated,@scenNumbers,scenWord,scenLimitKind,scenValueList,scenSelectOpen,scenSelectPair,scenSelectKey,scenEquals,scenCalcOperator,scenCalcFunction,scenCalcUnit
      \ nextgroup=scenLastAccessor
syn region  scenValueList contained matchgroup=scenPunct start=/\[/ end=/\]/
      \ end=/^\ze\%(scenario\|include\|world\|robot\|team\|plan\|expect\|bench\|param\|require\)\>\%(\s*\.\)\@!/
      \ contains=scenStray,scenPunct,scenOtherWord,scenComment,scenString,scenUnterminated,@scenNumbers,scenWord,scenLimitKind,scenValueList,scenCalcOperator,scenCalcFunction,scenCalcUnit
syn match   scenSelectOpen contained /\w\@1<=\[/
syn match   scenSelectPair contained /\%(\w\@1<=\[\|,\)\_s*\h\w*\ze\s*=/ contains=scenPunct,scenSelectKey
syn match   scenSelectKey contained /\<\h\w*\ze\s*=/
syn match   scenEquals contained /=/
syn match   scenOperator contained /<=\|>=\|==\|!=\|<\|>\|\~\|+-\|±\|[-+*\/]/
" Word operators and booleans followed by `.` are plan names (`not.found`).
syn match   scenLogical contained /\<\%(and\|or\|not\|where\)\>\.\@!/
syn match   scenBoolean contained /\<\%(true\|false\)\>\.\@!/

" --------------------------------------------------------------- param
" `param NAME = uniform(a, b) | normal(m, s) | int(a, b) | choice [...] | EXPR`:
" the value runs until the next statement.
syn region  scenParam matchgroup=scenStatement start=/\<param\>\%(\s*\.\)\@!/
      \ end=/\ze\.\@1<!\<\%(scenario\|include\|world\|robot\|team\|plan\|expect\|bench\|param\|require\)\>\%(\s*\.\)\@!/
      \ contains=scenStray,scenPunct,scenComment,scenString,scenUnterminated,@scenNumbers,scenParamRef,scenBadFunction,scenCalcFunction,scenChoice,scenCalcOperator,scenCalcUnit,scenEquals,scenParamName
syn match   scenParamName contained /\%(\<param\s\+\)\@<=\h\w*/
syn match   scenChoice contained /\<choice\>/
" The unit of a parenthesised expression: `(a + 10)deg`.
syn match   scenCalcUnit /)\@1<=\%(deg\|rad\)\%([[:alnum:]_.%]\)\@!/
syn sync minlines=200

" ---------------------------------------------------------------- links
hi def link scenTodo          Todo
hi def link scenComment       Comment
hi def link scenString        String
hi def link scenEscape        SpecialChar
hi def link scenBadEscape     Error
hi def link scenUnterminated  Error
hi def link scenNumber        Number
hi def link scenAngle         Number
hi def link scenPercent       Number
hi def link scenDuration      Number
hi def link scenUnit          Special
hi def link scenBadNumber     Error
hi def link scenExprNumber    Number
hi def link scenExprAngle     Number
hi def link scenExprPercent   Number
hi def link scenExprBadNumber Error
hi def link scenExprDuration  Error
hi def link scenStray         Error
hi def link scenBadFunction   Error
hi def link scenStatement     Statement
hi def link scenShape         Type
hi def link scenRobotShape    Type
hi def link scenScatterShape  Type
hi def link scenWorldKeyword  Keyword
hi def link scenRobotClause   Keyword
hi def link scenName          Function
hi def link scenPlanName      Function
hi def link scenBenchName     Function
hi def link scenBenchComment  Comment
hi def link scenObstacleName  Function
hi def link scenScatterName   Function
hi def link scenParamName     Function
hi def link scenChoice        Function
hi def link scenCalcOperator  Operator
hi def link scenArrow         Operator
hi def link scenCalcUnit      Special
hi def link scenPlanner       Structure
hi def link scenBadPlanner    Error
hi def link scenParamKey      Identifier
hi def link scenBenchKey      Identifier
hi def link scenSelectKey     Identifier
hi def link scenLimitKind     Identifier
hi def link scenWord          Constant
hi def link scenMetric        PreProc
hi def link scenOperator      Operator
hi def link scenEquals        Operator
hi def link scenFunction      Function
hi def link scenCalcFunction  Function
hi def link scenLogical       Operator
hi def link scenBoolean       Boolean
hi def link scenBrace         Delimiter

let b:current_syntax = 'scen'
let &cpo = s:cpo_save
unlet s:cpo_save
